/*
 * Listens on channel 1; on "hop N" moves its receiver to channel N. Writes, for each packet, the
 * step it was read, the receiver's channel then, its text, its signal strength and the emitter's
 * direction.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <webots/receiver.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag receiver = wb_robot_get_device("receiver");
  wb_receiver_enable(receiver, time_step);
  char path[1024];
  const char *dir = getenv("SWARM_LOG");
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  if (!out)
    return 1;
  fprintf(out, "{\"heard\": [");
  int steps = 0, count = 0;
  while (wb_robot_step(time_step) != -1 && steps < 30) {
    steps++;
    while (wb_receiver_get_queue_length(receiver) > 0) {
      char text[64];
      const int size = wb_receiver_get_data_size(receiver);
      snprintf(text, sizeof text, "%.*s", size < 63 ? size : 63, (const char *)wb_receiver_get_data(receiver));
      const double *d = wb_receiver_get_emitter_direction(receiver);
      fprintf(out, "%s[%d, %d, \"%s\", %.9g, %.9g, %.9g]", count++ ? ", " : "", steps,
              wb_receiver_get_channel(receiver), text, wb_receiver_get_signal_strength(receiver), d[0],
              d[1]);
      int channel;
      if (sscanf(text, "hop %d", &channel) == 1)
        wb_receiver_set_channel(receiver, channel);
      wb_receiver_next_packet(receiver);
    }
  }
  fprintf(out, "]}\n");
  fclose(out);
  wb_robot_cleanup();
  return 0;
}
