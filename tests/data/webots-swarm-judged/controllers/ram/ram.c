/*
 * Drives straight on at the wheel speed of its first argument for 3.5 s of simulated time,
 * reading its eight proximity sensors; writes the largest reading of ps0 and ps7 it saw.
 */
#include <stdio.h>
#include <stdlib.h>
#include <math.h>

#include <webots/distance_sensor.h>
#include <webots/motor.h>
#include <webots/robot.h>

int main(int argc, char **argv) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  const double speed = argc > 1 ? atof(argv[1]) : 0.0;
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, speed);
  wb_motor_set_velocity(right, speed);
  WbDeviceTag ps0 = wb_robot_get_device("ps0");
  WbDeviceTag ps7 = wb_robot_get_device("ps7");
  wb_distance_sensor_enable(ps0, time_step);
  wb_distance_sensor_enable(ps7, time_step);
  double most = 0.0;
  int steps = 0;
  while (wb_robot_step(time_step) != -1 && wb_robot_get_time() < 3.5) {
    steps++;
    const double front = fmax(wb_distance_sensor_get_value(ps0), wb_distance_sensor_get_value(ps7));
    if (front > most)
      most = front;
  }
  char path[1024];
  const char *dir = getenv("SWARM_LOG");
  snprintf(path, sizeof(path), "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  if (out) {
    fprintf(out, "{\"speed\": %g, \"steps\": %d, \"front_max\": %g}\n", speed, steps, most);
    fclose(out);
  }
  wb_robot_cleanup();
  return 0;
}
