/* Webots' Mouse and Joystick functions (reference manual, Mouse and Joystick pages): calls
   served by the robot's Python Mouse and Joystick, so that a C controller finds the headless
   run's mouse (no button, the pointer outside the view) and no joystick, as a Python one does. */
#include <math.h>
#include <stddef.h>

#include <webots/joystick.h>
#include <webots/mouse.h>

#include "call.h"
#include "link.h"

/* Starts a call of `function` (the robot's mouse or joystick, no device tag). */
static void input_call(const char *function) {
  link_start();
  call_begin(function);
}

/* The integer a call of `function` with no value answers. */
static int answered_int(const char *function) {
  input_call(function);
  call_end();
  return answer_int(0);
}

/* A call of `function` with one integer, answered by nothing. */
static void with_int(const char *function, int value) {
  input_call(function);
  call_int(value);
  call_end();
}

/* A call of `function` with one number, answered by nothing. */
static void with_double(const char *function, double value) {
  input_call(function);
  call_double(value);
  call_end();
}

void wb_mouse_enable(int sampling_period) {
  with_int("wb_mouse_enable", sampling_period);
}

void wb_mouse_disable(void) {
  answered_int("wb_mouse_disable");
}

int wb_mouse_get_sampling_period(void) {
  return answered_int("wb_mouse_get_sampling_period");
}

void wb_mouse_enable_3d_position(void) {
  answered_int("wb_mouse_enable_3d_position");
}

void wb_mouse_disable_3d_position(void) {
  answered_int("wb_mouse_disable_3d_position");
}

bool wb_mouse_is_3d_position_enabled(void) {
  return answered_int("wb_mouse_is_3d_position_enabled");
}

WbMouseState wb_mouse_get_state(void) {
  input_call("wb_mouse_get_state");
  call_end();
  int count = 0;
  const double *values = answer_doubles(0, &count);
  WbMouseState state = {false, false, false, NAN, NAN, NAN, NAN, NAN};
  if (values && count >= 8) {
    state.left = values[0] != 0.0;
    state.middle = values[1] != 0.0;
    state.right = values[2] != 0.0;
    state.u = values[3];
    state.v = values[4];
    state.x = values[5];
    state.y = values[6];
    state.z = values[7];
  }
  return state;
}

void wb_joystick_enable(int sampling_period) {
  with_int("wb_joystick_enable", sampling_period);
}

void wb_joystick_disable(void) {
  answered_int("wb_joystick_disable");
}

int wb_joystick_get_sampling_period(void) {
  return answered_int("wb_joystick_get_sampling_period");
}

bool wb_joystick_is_connected(void) {
  return answered_int("wb_joystick_is_connected");
}

const char *wb_joystick_get_model(void) {
  input_call("wb_joystick_get_model");
  call_end();
  return answer_kept_text(0, "wb_joystick_get_model", 0);
}

int wb_joystick_get_number_of_axes(void) {
  return answered_int("wb_joystick_get_number_of_axes");
}

int wb_joystick_get_axis_value(int axis) {
  input_call("wb_joystick_get_axis_value");
  call_int(axis);
  call_end();
  return answer_int(0);
}

int wb_joystick_get_number_of_povs(void) {
  return answered_int("wb_joystick_get_number_of_povs");
}

int wb_joystick_get_pov_value(int pov) {
  input_call("wb_joystick_get_pov_value");
  call_int(pov);
  call_end();
  return answer_int(0);
}

int wb_joystick_get_pressed_button(void) {
  return answered_int("wb_joystick_get_pressed_button");
}

void wb_joystick_set_constant_force(int level) {
  with_int("wb_joystick_set_constant_force", level);
}

void wb_joystick_set_constant_force_duration(double duration) {
  with_double("wb_joystick_set_constant_force_duration", duration);
}

void wb_joystick_set_auto_centering_gain(double gain) {
  with_double("wb_joystick_set_auto_centering_gain", gain);
}

void wb_joystick_set_resistance_gain(double gain) {
  with_double("wb_joystick_set_resistance_gain", gain);
}

void wb_joystick_set_force_axis(int axis) {
  with_int("wb_joystick_set_force_axis", axis);
}
