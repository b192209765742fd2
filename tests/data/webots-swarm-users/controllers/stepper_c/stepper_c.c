/*
 * Steps by the period in ms of its first argument for 0.5 s and notes the times of its first
 * six steps and its step count.
 */
#include <stdio.h>
#include <stdlib.h>

#include <webots/robot.h>

int main(int argc, char **argv) {
  wb_robot_init();
  const int period = argc > 1 ? atoi(argv[1]) : 32;
  double times[6];
  int steps = 0;
  while (wb_robot_step(period) != -1 && wb_robot_get_time() < 0.5 - 1e-9) {
    if (steps < 6)
      times[steps] = wb_robot_get_time();
    steps++;
  }
  char path[1024];
  const char *dir = getenv("SWARM_LOG");
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  if (out) {
    fprintf(out, "{\"steps\": %d, \"times\": [%g, %g, %g, %g, %g, %g]}\n", steps, times[0],
            times[1], times[2], times[3], times[4], times[5]);
    fclose(out);
  }
  wb_robot_cleanup();
  return 0;
}
