/* Drives ahead at 4 rad/s and says "step N" for 10 steps, stops its wheels, then leaves:
 * wb_robot_cleanup() and return, while the others run on. */
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <webots/emitter.h>
#include <webots/motor.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag tx = wb_robot_get_device("emitter");
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, 4.0);
  wb_motor_set_velocity(right, 4.0);
  for (int steps = 1; steps <= 10; steps++) {
    if (wb_robot_step(time_step) == -1)
      break;
    char packet[32];
    snprintf(packet, sizeof packet, "step %d", steps);
    wb_emitter_send(tx, packet, (int)strlen(packet) + 1);
  }
  wb_motor_set_velocity(left, 0.0);
  wb_motor_set_velocity(right, 0.0);
  wb_robot_step(time_step);
  wb_robot_cleanup();
  return 0;
}
