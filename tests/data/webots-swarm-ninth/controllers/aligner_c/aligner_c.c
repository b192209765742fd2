/*
 * Heading alignment in C: each step it sends the yaw its InertialUnit reads and turns towards
 * the circular mean of its own and every heading it heard, driving at 1 rad/s.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <webots/emitter.h>
#include <webots/inertial_unit.h>
#include <webots/motor.h>
#include <webots/receiver.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag imu = wb_robot_get_device("imu");
  WbDeviceTag emitter = wb_robot_get_device("emitter");
  WbDeviceTag receiver = wb_robot_get_device("receiver");
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_inertial_unit_enable(imu, time_step);
  wb_receiver_enable(receiver, time_step);
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  double yaw = 0.0;
  int steps = 0;
  char text[64];
  while (wb_robot_step(time_step) != -1 && steps < 200) {
    steps++;
    yaw = wb_inertial_unit_get_roll_pitch_yaw(imu)[2];
    double sx = cos(yaw), sy = sin(yaw);
    while (wb_receiver_get_queue_length(receiver) > 0) {
      const double other = atof((const char *)wb_receiver_get_data(receiver));
      wb_receiver_next_packet(receiver);
      sx += cos(other);
      sy += sin(other);
    }
    const double mean = atan2(sy, sx);
    const double error = atan2(sin(mean - yaw), cos(mean - yaw));
    double turn = 2.0 * error;
    turn = turn > 1.0 ? 1.0 : (turn < -1.0 ? -1.0 : turn);
    wb_motor_set_velocity(left, 1.0 - turn);
    wb_motor_set_velocity(right, 1.0 + turn);
    snprintf(text, sizeof text, "%.17g", yaw);
    wb_emitter_send(emitter, text, strlen(text) + 1);
  }
  wb_motor_set_velocity(left, 0.0);
  wb_motor_set_velocity(right, 0.0);
  char path[1024];
  const char *dir = getenv("SWARM_LOG");
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  if (out) {
    fprintf(out, "{\"last_yaw\": %.17g, \"steps\": %d}\n", yaw, steps);
    fclose(out);
  }
  wb_robot_cleanup();
  return 0;
}
