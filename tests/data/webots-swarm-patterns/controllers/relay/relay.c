/*
 * A chain of e-pucks passing orders on: the head broadcasts [sequence number, wheel speed] on
 * the channel of its second argument, 0.5 m far; every other robot listens on the channel of
 * its first argument, drives at the speed it heard last and passes each packet on over the
 * channel of its second argument ("none": it passes nothing on).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <webots/emitter.h>
#include <webots/motor.h>
#include <webots/receiver.h>
#include <webots/robot.h>

#define LAST_STEP 60

int main(int argc, char **argv) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  const int is_head = argc > 1 && strcmp(argv[1], "head") == 0;
  const int passes_on = argc > 2 && strcmp(argv[2], "none") != 0;
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, 0.0);
  wb_motor_set_velocity(right, 0.0);
  WbDeviceTag emitter = wb_robot_get_device("emitter");
  WbDeviceTag receiver = wb_robot_get_device("receiver");
  if (passes_on) {
    wb_emitter_set_channel(emitter, atoi(argv[2]));
    wb_emitter_set_range(emitter, 0.5);
  }
  if (!is_head && argc > 1) {
    wb_receiver_set_channel(receiver, atoi(argv[1]));
    wb_receiver_enable(receiver, time_step);
  }
  int steps = 0, heard = 0, first_heard = -1, size = 0, first_sequence = -1, last_sequence = -1;
  double strength = 0.0, speed = 0.0;
  while (wb_robot_step(time_step) != -1) {
    steps++;
    if (steps > LAST_STEP)
      break;
    if (is_head) {
      const double order[2] = {steps, steps <= 40 ? 3.0 : 0.0};
      wb_emitter_send(emitter, order, sizeof(order));
      continue;
    }
    while (wb_receiver_get_queue_length(receiver) > 0) {
      const double *order = (const double *)wb_receiver_get_data(receiver);
      if (first_heard < 0) {
        first_heard = steps;
        size = wb_receiver_get_data_size(receiver);
        strength = wb_receiver_get_signal_strength(receiver);
        first_sequence = (int)order[0];
      }
      heard++;
      last_sequence = (int)order[0];
      speed = order[1];
      if (passes_on)
        wb_emitter_send(emitter, order, 2 * sizeof(double));
      wb_receiver_next_packet(receiver);
    }
    wb_motor_set_velocity(left, speed);
    wb_motor_set_velocity(right, speed);
  }
  const char *folder = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof(path), "%s/%s.json", folder ? folder : ".", wb_robot_get_name());
  FILE *log = fopen(path, "w");
  if (log) {
    fprintf(log,
            "{\"steps\": %d, \"heard\": %d, \"first_heard\": %d, \"size\": %d, \"strength\": %.6f, "
            "\"first_sequence\": %d, \"last_sequence\": %d, \"speed\": %.3f}\n",
            steps, heard, first_heard, size, strength, first_sequence, last_sequence, speed);
    fclose(log);
  }
  wb_robot_cleanup();
  return 0;
}
