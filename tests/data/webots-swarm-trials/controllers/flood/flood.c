/*
 * Sends ten packets of 100 bytes each step, numbered 10 * step + i; notes how many sends the
 * emitter accepted (its bufferSize is 800 bytes a step).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <webots/emitter.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag tx = wb_robot_get_device("tx");
  int accepted_first = -1;
  int steps = 0;
  while (wb_robot_step(time_step) != -1 && steps < 30) {
    steps++;
    int accepted = 0;
    for (int i = 0; i < 10; i++) {
      int packet[25];
      memset(packet, 0, sizeof(packet));
      packet[0] = 10 * steps + i;
      accepted += wb_emitter_send(tx, packet, sizeof(packet));
    }
    if (accepted_first < 0)
      accepted_first = accepted;
  }
  const char *dir = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof(path), "%s/flood.json", dir ? dir : ".");
  FILE *out = fopen(path, "w");
  if (out) {
    fprintf(out, "{\"accepted_a_step\": %d, \"buffer\": %d, \"steps\": %d}\n", accepted_first,
            wb_emitter_get_buffer_size(tx), steps);
    fclose(out);
  }
  wb_robot_cleanup();
  return 0;
}
