/* A wall avoider in C, written for mazesim's tests: it reads the e-puck's front proximity
   sensors and its encoders, steers away from walls and prints a line a second. Its twin in
   Python, wall_avoider_twin.py, applies the same rule. */
#include <math.h>
#include <stdio.h>

#include <webots/device.h>
#include <webots/distance_sensor.h>
#include <webots/led.h>
#include <webots/motor.h>
#include <webots/position_sensor.h>
#include <webots/robot.h>

#include "steering.h"

int main(void) {
  wb_robot_init();
  int step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag front[2] = {wb_robot_get_device("ps7"), wb_robot_get_device("ps0")};
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  WbDeviceTag encoder = wb_robot_get_device("left wheel sensor");
  WbDeviceTag led = wb_robot_get_device("led0");
  for (int i = 0; i < 2; i++)
    wb_distance_sensor_enable(front[i], step);
  wb_position_sensor_enable(encoder, step);
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, 0.0);
  wb_motor_set_velocity(right, 0.0);
  printf("devices %d, %s is a %s sensor\n", wb_robot_get_number_of_devices(),
         wb_device_get_name(front[1]),
         wb_device_get_node_type(front[1]) == WB_NODE_DISTANCE_SENSOR ? "distance" : "other");
  int steps = 0;
  while (wb_robot_step(step) != -1) {
    double left_speed, right_speed;
    steer(wb_distance_sensor_get_value(front[0]), wb_distance_sensor_get_value(front[1]),
          &left_speed, &right_speed);
    wb_motor_set_velocity(left, left_speed);
    wb_motor_set_velocity(right, right_speed);
    wb_led_set(led, left_speed < 0.0 || right_speed < 0.0);
    if (++steps % 31 == 0)
      printf("t %.3f encoder %.4f\n", wb_robot_get_time(), wb_position_sensor_get_value(encoder));
  }
  wb_robot_cleanup();
  return 0;
}
