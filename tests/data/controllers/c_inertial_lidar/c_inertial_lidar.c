/* Reads an inertial unit and a lidar as inertial_lidar_twin.py does, printed alike. */
#include <math.h>
#include <stdio.h>

#include <webots/inertial_unit.h>
#include <webots/lidar.h>
#include <webots/motor.h>
#include <webots/robot.h>

static void show(const char *label, const double *values, int count) {
  printf("%s", label);
  for (int i = 0; i < count; i++) {
    if (isnan(values[i]))
      printf(" none");
    else
      printf(" %.6f", values[i]);
  }
  printf("\n");
}

static const char *number(double value, char *text) {
  if (isnan(value))
    return "none";
  sprintf(text, "%.6f", value);
  return text;
}

int main(void) {
  wb_robot_init();
  int step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag imu = wb_robot_get_device("inertial unit");
  WbDeviceTag lidar = wb_robot_get_device("lidar");
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_inertial_unit_enable(imu, step);
  wb_lidar_enable(lidar, step);
  wb_lidar_enable_point_cloud(lidar);
  wb_motor_set_control_pid(left, 8.0, 0.0, 0.0);
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, -1.0);
  wb_motor_set_velocity(right, 1.0);
  int n = 0;
  char fov[32], range[32];
  while (wb_robot_step(step) != -1) {
    if (++n % 8)
      continue;
    show("rpy", wb_inertial_unit_get_roll_pitch_yaw(imu), 3);
    show("quaternion", wb_inertial_unit_get_quaternion(imu), 4);
    const float *ranges = wb_lidar_get_range_image(lidar);
    int resolution = wb_lidar_get_horizontal_resolution(lidar);
    int layers = wb_lidar_get_number_of_layers(lidar);
    if (ranges)
      printf("ranges %d", resolution * layers);
    else
      printf("ranges none");
    printf(" resolution %d layers %d\n", resolution, layers);
    const WbLidarPoint *cloud = wb_lidar_get_point_cloud(lidar);
    printf("cloud %s points %d fov %s max %s\n", cloud ? "some" : "none",
           wb_lidar_get_number_of_points(lidar), number(wb_lidar_get_fov(lidar), fov),
           number(wb_lidar_get_max_range(lidar), range));
    if (cloud && ranges) {  /* the nearest point */
      int k = 0;
      for (int i = 1; i < resolution * layers; i++)
        if (ranges[i] < ranges[k])
          k = i;
      printf("point %d %.4f %.4f %.4f %d %.4f range %.4f\n", k, cloud[k].x, cloud[k].y, cloud[k].z,
             cloud[k].layer_id, cloud[k].time, ranges[k]);
    }
  }
  wb_robot_cleanup();
  return 0;
}
