/* Stands still and sends "infra-red" from its infra-red emitter and "radio" from its radio
   emitter at every step, for 20 steps (the C twin of the swarm's beacon). */
#include <string.h>

#include <webots/emitter.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  const WbDeviceTag infra_red = wb_robot_get_device("infra-red emitter");
  const WbDeviceTag radio = wb_robot_get_device("radio emitter");
  for (int steps = 0; steps < 20; steps++) {
    wb_emitter_send(infra_red, "infra-red", (int)strlen("infra-red") + 1);
    wb_emitter_send(radio, "radio", (int)strlen("radio") + 1);
    if (wb_robot_step(time_step) == -1)
      break;
  }
  wb_robot_cleanup();
  return 0;
}
