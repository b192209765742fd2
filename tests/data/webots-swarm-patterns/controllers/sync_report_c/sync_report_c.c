/* Says whether its robot's simulation waits for it (the robot's synchronization field). */
#include <stdio.h>
#include <stdlib.h>

#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  int steps = 0;
  while (steps < 20 && wb_robot_step(time_step) != -1)
    steps++;
  const char *folder = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof(path), "%s/%s.json", folder ? folder : ".", wb_robot_get_name());
  FILE *log = fopen(path, "w");
  if (log) {
    fprintf(log, "{\"name\": \"%s\", \"synchronization\": %s, \"steps\": %d}\n", wb_robot_get_name(),
            wb_robot_get_synchronization() ? "true" : "false", steps);
    fclose(log);
  }
  wb_robot_cleanup();
  return 0;
}
