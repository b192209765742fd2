/* Reads the GPS and the inertial unit (its angles and its quaternion) before the first step,
   then drives straight ahead at 4 rad/s and reads the GPS's speed (m/s), its speed vector and
   the yaw (rad); writes what it read as JSON into $SWARM_LOG/gps_speed_c.json. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <webots/gps.h>
#include <webots/inertial_unit.h>
#include <webots/motor.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag gps = wb_robot_get_device("gps");
  WbDeviceTag inertial = wb_robot_get_device("inertial unit");
  wb_gps_enable(gps, time_step);
  wb_inertial_unit_enable(inertial, time_step);
  const double *early = wb_gps_get_values(gps);
  const int early_nan = isnan(early[0]) && isnan(early[1]) && isnan(early[2]) &&
                        isnan(wb_gps_get_speed(gps)) &&
                        isnan(wb_inertial_unit_get_roll_pitch_yaw(inertial)[2]);
  const double *quaternion = wb_inertial_unit_get_quaternion(inertial);
  int quaternion_nan = 0;
  for (int i = 0; i < 4; i++)
    quaternion_nan += isnan(quaternion[i]) != 0;
  const char *sides[2] = {"left wheel motor", "right wheel motor"};
  for (int i = 0; i < 2; i++) {
    WbDeviceTag motor = wb_robot_get_device(sides[i]);
    wb_motor_set_position(motor, INFINITY);
    wb_motor_set_velocity(motor, 4.0);
  }
  for (int i = 0; i < 20; i++)
    wb_robot_step(time_step);
  const double *where = wb_gps_get_values(gps);
  const double *velocity = wb_gps_get_speed_vector(gps);
  const char *dir = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  fprintf(out, "{\"early_nan\": %d, \"quaternion_nan\": %d, ", early_nan, quaternion_nan);
  fprintf(out, "\"speed\": %.9g, \"vector\": [%.9g, %.9g, %.9g], ", wb_gps_get_speed(gps),
          velocity[0], velocity[1], velocity[2]);
  fprintf(out, "\"where\": [%.9g, %.9g, %.9g], \"yaw\": %.9g}\n", where[0], where[1], where[2],
          wb_inertial_unit_get_roll_pitch_yaw(inertial)[2]);
  fclose(out);
  wb_robot_cleanup();
  return 0;
}
