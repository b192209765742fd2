/* Sends two packets a step, "<name>:<step>:0" and "<name>:<step>:1", on the E-puck's
 * emitter (channel 1), for 20 steps. */
#include <stdio.h>
#include <string.h>
#include <webots/emitter.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag tx = wb_robot_get_device("emitter");
  int steps = 0;
  while (wb_robot_step(time_step) != -1 && steps < 20) {
    steps++;
    for (int k = 0; k < 2; k++) {
      char packet[64];
      snprintf(packet, sizeof packet, "%s:%d:%d", wb_robot_get_name(), steps, k);
      wb_emitter_send(tx, packet, (int)strlen(packet) + 1);
    }
  }
  wb_robot_cleanup();
  return 0;
}
