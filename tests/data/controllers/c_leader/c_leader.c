/* The C twin of tests/data/webots-swarm/controllers/leader/leader.py: broadcasts "go" for 30
   steps, then "stop"; collects the followers' acknowledgements on channel 2. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <webots/emitter.h>
#include <webots/receiver.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag emitter = wb_robot_get_device("emitter");
  wb_emitter_set_range(emitter, 0.8); /* the E-puck PROTO sets no range: orders reach 0.8 m only */
  WbDeviceTag receiver = wb_robot_get_device("receiver");
  wb_receiver_set_channel(receiver, 2);
  wb_receiver_enable(receiver, time_step);
  static char acknowledgements[256][64];
  int heard = 0, steps = 0;
  while (wb_robot_step(time_step) != -1) {
    steps++;
    while (wb_receiver_get_queue_length(receiver) > 0) {
      int size = wb_receiver_get_data_size(receiver);
      if (heard < 256 && size < 64)
        memcpy(acknowledgements[heard++], wb_receiver_get_data(receiver), (size_t)size + 1);
      wb_receiver_next_packet(receiver);
    }
    const char *order = steps <= 30 ? "go" : "stop";
    wb_emitter_send(emitter, order, (int)strlen(order));
    if (steps == 60)
      break;
  }
  char path[4096];
  snprintf(path, sizeof path, "%s/leader.json", getenv("SWARM_LOG"));
  FILE *log = fopen(path, "w");
  fprintf(log, "{\"steps\": %d, \"acknowledgements\": [", steps);
  for (int i = 0; i < heard; i++)
    fprintf(log, "%s\"%s\"", i ? ", " : "", acknowledgements[i]);
  fprintf(log, "]}");
  fclose(log);
  wb_robot_cleanup();
  return 0;
}
