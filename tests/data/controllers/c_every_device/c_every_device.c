/* Reads the e-puck's camera, accelerometer, gyro, light sensor, encoders and keyboard and prints
   them every 8 steps, while turning; every_device_twin.py prints the same in Python. */
#include <stdio.h>

#include <webots/accelerometer.h>
#include <webots/camera.h>
#include <webots/gyro.h>
#include <webots/keyboard.h>
#include <webots/light_sensor.h>
#include <webots/motor.h>
#include <webots/position_sensor.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  int step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag camera = wb_robot_get_device("camera");
  WbDeviceTag accelerometer = wb_robot_get_device("accelerometer");
  WbDeviceTag gyro = wb_robot_get_device("gyro");
  WbDeviceTag light = wb_robot_get_device("ls0");
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  WbDeviceTag encoder = wb_motor_get_position_sensor(right);
  wb_camera_enable(camera, 2 * step);
  wb_accelerometer_enable(accelerometer, step);
  wb_gyro_enable(gyro, step);
  wb_light_sensor_enable(light, step);
  wb_position_sensor_enable(encoder, step);
  wb_keyboard_enable(step);
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, -2.0);
  wb_motor_set_velocity(right, 3.0);
  int width = wb_camera_get_width(camera), height = wb_camera_get_height(camera);
  printf("camera %dx%d\n", width, height);
  for (int n = 1; wb_robot_step(step) != -1; n++) {
    for (int key = wb_keyboard_get_key(); key != -1; key = wb_keyboard_get_key())
      printf("key %d at %.3f\n", key, wb_robot_get_time());
    if (n % 8)
      continue;
    const unsigned char *image = wb_camera_get_image(camera);
    long sum = 0;
    for (int i = 0; image && i < 4 * width * height; i++)
      sum += image[i];
    const double *a = wb_accelerometer_get_values(accelerometer);
    const double *g = wb_gyro_get_values(gyro);
    printf("image %ld red %d\n", sum, image ? wb_camera_image_get_red(image, width, 3, 4) : -1);
    printf("a %.6f %.6f %.6f g %.6f %.6f %.6f\n", a[0], a[1], a[2], g[0], g[1], g[2]);
    printf("light %.6f encoder %.6f\n", wb_light_sensor_get_value(light),
           wb_position_sensor_get_value(encoder));
  }
  wb_robot_cleanup();
  return 0;
}
