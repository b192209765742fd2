/* The C twin of tests/data/webots-swarm/controllers/follower/follower.py: drives forward while
   the leader's last order is "go" and acknowledges each order on channel 2. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <webots/emitter.h>
#include <webots/motor.h>
#include <webots/receiver.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const char *name = wb_robot_get_name();
  int time_step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, 0.0);
  wb_motor_set_velocity(right, 0.0);
  WbDeviceTag emitter = wb_robot_get_device("emitter");
  wb_emitter_set_channel(emitter, 2);
  WbDeviceTag receiver = wb_robot_get_device("receiver");
  wb_receiver_enable(receiver, time_step);
  static char orders[256][16];
  int count = 0, steps = 0, first_heard = -1;
  double strength = NAN, direction[3] = {NAN, NAN, NAN};
  while (wb_robot_step(time_step) != -1) {
    steps++;
    while (wb_receiver_get_queue_length(receiver) > 0) {
      if (first_heard < 0) {
        first_heard = steps;
        strength = wb_receiver_get_signal_strength(receiver);
        memcpy(direction, wb_receiver_get_emitter_direction(receiver), sizeof direction);
      }
      const char *order = wb_receiver_get_string(receiver);
      if (count < 256)
        snprintf(orders[count++], sizeof orders[0], "%s", order);
      wb_receiver_next_packet(receiver);
      char acknowledgement[64];
      snprintf(acknowledgement, sizeof acknowledgement, "%s %s", name, orders[count - 1]);
      wb_emitter_send(emitter, acknowledgement, (int)strlen(acknowledgement));
    }
    double speed = count > 0 && strcmp(orders[count - 1], "go") == 0 ? 4.0 : 0.0;
    wb_motor_set_velocity(left, speed);
    wb_motor_set_velocity(right, speed);
    if (steps == 60)
      break;
  }
  char path[4096];
  snprintf(path, sizeof path, "%s/%s.json", getenv("SWARM_LOG"), name);
  FILE *log = fopen(path, "w");
  if (first_heard < 0)
    fprintf(log, "{\"first_heard\": null, \"orders\": [");
  else
    fprintf(log, "{\"first_heard\": %d, \"orders\": [", first_heard);
  for (int i = 0; i < count; i++)
    fprintf(log, "%s\"%s\"", i ? ", " : "", orders[i]);
  if (first_heard < 0)
    fprintf(log, "], \"strengths\": []}");
  else
    fprintf(log, "], \"strengths\": [%.17g, [%.17g, %.17g, %.17g]]}", strength, direction[0],
            direction[1], direction[2]);
  fclose(log);
  wb_robot_cleanup();
  return 0;
}
