/*
 * Goes to the goal (x, y) of its second and third arguments, steering by the pose a
 * supervisor sends it on the channel of its first argument; stops within 2 cm.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include <webots/motor.h>
#include <webots/receiver.h>
#include <webots/robot.h>

int main(int argc, char **argv) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  const int channel = atoi(argv[1]);
  const double goal_x = atof(argv[2]), goal_y = atof(argv[3]);
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, 0.0);
  wb_motor_set_velocity(right, 0.0);
  WbDeviceTag receiver = wb_robot_get_device("receiver");
  wb_receiver_set_channel(receiver, channel);
  wb_receiver_enable(receiver, time_step);
  int heard = 0, arrived = -1, steps = 0;
  double x = 0.0, y = 0.0;
  while (wb_robot_step(time_step) != -1) {
    steps++;
    while (wb_receiver_get_queue_length(receiver) > 0) {
      const double *pose = (const double *)wb_receiver_get_data(receiver);
      x = pose[0];
      y = pose[1];
      const double heading = pose[2];
      heard++;
      const double dx = goal_x - x, dy = goal_y - y;
      const double distance = sqrt(dx * dx + dy * dy);
      double turn = atan2(dy, dx) - heading;
      turn = atan2(sin(turn), cos(turn));
      double forward = distance < 0.02 ? 0.0 : (fabs(turn) > 0.5 ? 0.0 : 4.0);
      double spin = distance < 0.02 ? 0.0 : 3.0 * turn;
      if (spin > 3.0) spin = 3.0;
      if (spin < -3.0) spin = -3.0;
      if (distance < 0.02 && arrived < 0)
        arrived = steps;
      wb_motor_set_velocity(left, forward - spin);
      wb_motor_set_velocity(right, forward + spin);
      wb_receiver_next_packet(receiver);
    }
    if (steps >= 500)
      break;
  }
  char path[1024];
  const char *dir = getenv("SWARM_LOG");
  snprintf(path, sizeof(path), "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  if (out) {
    fprintf(out, "{\"heard\": %d, \"arrived\": %d, \"x\": %.6f, \"y\": %.6f}\n", heard, arrived, x, y);
    fclose(out);
  }
  wb_robot_cleanup();
  return 0;
}
