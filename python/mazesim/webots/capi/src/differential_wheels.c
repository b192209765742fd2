/* Webots 8's DifferentialWheels functions on the e-puck's wheel motors and position sensors. */
#include <math.h>
#include <stdio.h>

#include <webots/device.h>
#include <webots/differential_wheels.h>
#include <webots/motor.h>
#include <webots/position_sensor.h>
#include <webots/robot.h>

#include "link.h"

/* The e-puck's DifferentialWheels fields in Webots 8: speedUnit, maxSpeed, encoderResolution. */
#define SPEED_UNIT 0.00628
#define MAX_SPEED 1000.0
#define ENCODER_RESOLUTION 159.23

static WbDeviceTag motors[2], sensors[2];
static double speeds[2], encoder_offsets[2];
static int found;

/* The wheel motors and sensors, found by their names (printing Webots' message if absent). */
static int wheels(void) {
  if (!found) {
    found = 1;
    motors[0] = wb_robot_get_device("left wheel motor");
    motors[1] = wb_robot_get_device("right wheel motor");
    sensors[0] = wb_robot_get_device("left wheel sensor");
    sensors[1] = wb_robot_get_device("right wheel sensor");
  }
  return motors[0] && motors[1];
}

static double clamp(double speed) {
  return speed > MAX_SPEED ? MAX_SPEED : (speed < -MAX_SPEED ? -MAX_SPEED : speed);
}

void wb_differential_wheels_set_speed(double left, double right) {
  if (!wheels())
    return;
  speeds[0] = clamp(left);
  speeds[1] = clamp(right);
  for (int side = 0; side < 2; side++) {
    wb_motor_set_position(motors[side], INFINITY);
    wb_motor_set_velocity(motors[side], speeds[side] * SPEED_UNIT);
  }
}

double wb_differential_wheels_get_left_speed(void) {
  return speeds[0];
}

double wb_differential_wheels_get_right_speed(void) {
  return speeds[1];
}

double wb_differential_wheels_get_max_speed(void) {
  return MAX_SPEED;
}

double wb_differential_wheels_get_speed_unit(void) {
  return SPEED_UNIT;
}

void wb_differential_wheels_enable_encoders(int period) {
  if (!wheels() || !sensors[0] || !sensors[1])
    return;
  wb_position_sensor_enable(sensors[0], period);
  wb_position_sensor_enable(sensors[1], period);
}

void wb_differential_wheels_disable_encoders(void) {
  if (!wheels() || !sensors[0] || !sensors[1])
    return;
  wb_position_sensor_disable(sensors[0]);
  wb_position_sensor_disable(sensors[1]);
}

int wb_differential_wheels_get_encoders_sampling_period(void) {
  return wheels() && sensors[0] ? wb_position_sensor_get_sampling_period(sensors[0]) : 0;
}

/* The encoder before its offset: 0 until the first reading. */
static double raw_encoder(int side) {
  if (!wheels() || !sensors[side])
    return 0.0;
  double angle = wb_position_sensor_get_value(sensors[side]);
  return isnan(angle) ? 0.0 : angle * ENCODER_RESOLUTION;
}

double wb_differential_wheels_get_left_encoder(void) {
  return raw_encoder(0) - encoder_offsets[0];
}

double wb_differential_wheels_get_right_encoder(void) {
  return raw_encoder(1) - encoder_offsets[1];
}

void wb_differential_wheels_set_encoders(double left, double right) {
  encoder_offsets[0] = raw_encoder(0) - left;
  encoder_offsets[1] = raw_encoder(1) - right;
}
