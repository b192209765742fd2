/* Reads the left wheel's position sensor before it is enabled, after it is enabled but before
   a step, and after ten steps of the wheel turning at 2 rad/s; writes what it read as JSON into
   $SWARM_LOG/position_sensor_c.json. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <webots/motor.h>
#include <webots/position_sensor.h>
#include <webots/robot.h>

static void number(FILE *out, const char *key, double value) {
  if (isnan(value))
    fprintf(out, "\"%s\": \"nan\"", key);
  else
    fprintf(out, "\"%s\": %.9g", key, value);
}

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag motor = wb_robot_get_device("left wheel motor");
  WbDeviceTag sensor = wb_robot_get_device("left wheel sensor");
  const double unset = wb_position_sensor_get_value(sensor);
  const int period_unset = wb_position_sensor_get_sampling_period(sensor);
  wb_position_sensor_enable(sensor, time_step);
  const double enabled = wb_position_sensor_get_value(sensor);
  wb_robot_step(time_step);
  const double first = wb_position_sensor_get_value(sensor);
  wb_motor_set_position(motor, INFINITY);
  wb_motor_set_velocity(motor, 2.0);
  for (int i = 0; i < 10; i++)
    wb_robot_step(time_step);
  const double turned = wb_position_sensor_get_value(sensor);
  const char *dir = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  fprintf(out, "{");
  number(out, "unset", unset);
  fprintf(out, ", \"period_unset\": %d, ", period_unset);
  number(out, "enabled", enabled);
  fprintf(out, ", ");
  number(out, "first", first);
  fprintf(out, ", ");
  number(out, "turned", turned);
  fprintf(out, ", \"period\": %d, \"type\": %d, \"rotational\": %d, \"motor_matches\": %d, "
               "\"sensor_matches\": %d}\n",
          wb_position_sensor_get_sampling_period(sensor), (int)wb_position_sensor_get_type(sensor),
          (int)WB_ROTATIONAL, wb_position_sensor_get_motor(sensor) == motor,
          wb_motor_get_position_sensor(motor) == sensor);
  fclose(out);
  wb_robot_cleanup();
  return 0;
}
