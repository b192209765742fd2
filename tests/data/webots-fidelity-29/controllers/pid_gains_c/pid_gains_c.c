/* pid_gains.py in C: the left wheel to 3 rad with wb_motor_set_control_pid(2, 0.5, 0.01), the
   right with the default gains; writes both encoders after each step as JSON. */
#include <stdio.h>
#include <stdlib.h>
#include <webots/motor.h>
#include <webots/position_sensor.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  WbDeviceTag left_sensor = wb_motor_get_position_sensor(left);
  WbDeviceTag right_sensor = wb_motor_get_position_sensor(right);
  wb_position_sensor_enable(left_sensor, time_step);
  wb_position_sensor_enable(right_sensor, time_step);
  wb_motor_set_control_pid(left, 2.0, 0.5, 0.01);
  wb_motor_set_position(left, 3.0);
  wb_motor_set_position(right, 3.0);
  const char *dir = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  fprintf(out, "{\"angles\": [");
  for (int step = 0; step < 40 && wb_robot_step(time_step) != -1; step++)
    fprintf(out, "%s[%.17g, %.17g]", step ? ", " : "", wb_position_sensor_get_value(left_sensor),
            wb_position_sensor_get_value(right_sensor));
  fprintf(out, "]}\n");
  fclose(out);
  wb_robot_cleanup();
  return 0;
}
