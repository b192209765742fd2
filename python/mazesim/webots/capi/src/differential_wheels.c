/* Webots 8's DifferentialWheels functions: calls over the link, run on the robot's Python
   DifferentialDrive (mazesim/webots/differential_drive.py), which reads the world's node fields
   and keeps Webots' rules, so that a C controller drives as its Python twin does. */
#include <webots/differential_wheels.h>

#include "call.h"
#include "link.h"

static void drive_call(const char *function) {
  link_start();
  call_begin(function);
}

static double answered_double(void) {
  call_end();
  return answer_double(0);
}

void wb_differential_wheels_set_speed(double left, double right) {
  drive_call("wb_differential_wheels_set_speed");
  call_double(left);
  call_double(right);
  call_end();
}

double wb_differential_wheels_get_left_speed(void) {
  drive_call("wb_differential_wheels_get_left_speed");
  return answered_double();
}

double wb_differential_wheels_get_right_speed(void) {
  drive_call("wb_differential_wheels_get_right_speed");
  return answered_double();
}

double wb_differential_wheels_get_max_speed(void) {
  drive_call("wb_differential_wheels_get_max_speed");
  return answered_double();
}

double wb_differential_wheels_get_speed_unit(void) {
  drive_call("wb_differential_wheels_get_speed_unit");
  return answered_double();
}

void wb_differential_wheels_enable_encoders(int period) {
  drive_call("wb_differential_wheels_enable_encoders");
  call_int(period);
  call_end();
}

void wb_differential_wheels_disable_encoders(void) {
  drive_call("wb_differential_wheels_disable_encoders");
  call_end();
}

int wb_differential_wheels_get_encoders_sampling_period(void) {
  drive_call("wb_differential_wheels_get_encoders_sampling_period");
  call_end();
  return answer_int(0);
}

double wb_differential_wheels_get_left_encoder(void) {
  drive_call("wb_differential_wheels_get_left_encoder");
  return answered_double();
}

double wb_differential_wheels_get_right_encoder(void) {
  drive_call("wb_differential_wheels_get_right_encoder");
  return answered_double();
}

void wb_differential_wheels_set_encoders(double left, double right) {
  drive_call("wb_differential_wheels_set_encoders");
  call_double(left);
  call_double(right);
  call_end();
}
