/*
 * Sends, after each of its 20 steps, a struct of its step number, a speed and the simulated
 * time, and reads the Python robot's packed structs (int32 step, float x, float y).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <webots/emitter.h>
#include <webots/receiver.h>
#include <webots/robot.h>

typedef struct {
  int32_t step;
  float speed;
  double time;
} Report;

typedef struct {
  int32_t step;
  float x;
  float y;
} Reply;

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag emitter = wb_robot_get_device("emitter");
  WbDeviceTag receiver = wb_robot_get_device("receiver");
  wb_receiver_enable(receiver, time_step);
  int step = 0, heard = 0, last_step = -1, bad_size = 0;
  float sum_x = 0.0f;
  while (wb_robot_step(time_step) != -1 && step < 20) {
    step++;
    while (wb_receiver_get_queue_length(receiver) > 0) {
      if (wb_receiver_get_data_size(receiver) != (int)sizeof(Reply))
        bad_size++;
      else {
        Reply reply;
        memcpy(&reply, wb_receiver_get_data(receiver), sizeof reply);
        last_step = reply.step;
        sum_x += reply.x;
        heard++;
      }
      wb_receiver_next_packet(receiver);
    }
    Report report = {step, 0.5f * step, wb_robot_get_time()};
    wb_emitter_send(emitter, &report, sizeof report);
  }
  char path[1024];
  const char *dir = getenv("SWARM_LOG");
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  if (out) {
    fprintf(out, "{\"size\": %d, \"heard\": %d, \"last_step\": %d, \"bad_size\": %d, \"sum_x\": %.4f}\n",
            (int)sizeof(Report), heard, last_step, bad_size, sum_x);
    fclose(out);
  }
  wb_robot_cleanup();
  return 0;
}
