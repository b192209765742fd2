/* Drives forward at full speed for 100 steps and logs its two front proximity readings. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <webots/distance_sensor.h>
#include <webots/motor.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  WbDeviceTag ps0 = wb_robot_get_device("ps0");
  WbDeviceTag ps7 = wb_robot_get_device("ps7");
  wb_distance_sensor_enable(ps0, time_step);
  wb_distance_sensor_enable(ps7, time_step);
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  const double speed = wb_motor_get_max_velocity(left);
  wb_motor_set_velocity(left, speed);
  wb_motor_set_velocity(right, speed);
  int steps = 0;
  while (steps < 100 && wb_robot_step(time_step) != -1)
    steps++;
  const char *folder = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof(path), "%s/%s.json", folder ? folder : ".", wb_robot_get_name());
  FILE *log = fopen(path, "w");
  if (log) {
    fprintf(log, "{\"steps\": %d, \"ps0\": %.3f, \"ps7\": %.3f}\n", steps,
            wb_distance_sensor_get_value(ps0), wb_distance_sensor_get_value(ps7));
    fclose(log);
  }
  wb_robot_cleanup();
  return 0;
}
