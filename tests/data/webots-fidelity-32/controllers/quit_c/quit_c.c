/* A supervisor that takes three steps, quits the simulation with status 3 and steps once more;
   writes each step's return value and the time as JSON into $SWARM_LOG/quit_c.json. */
#include <stdio.h>
#include <stdlib.h>
#include <webots/robot.h>
#include <webots/supervisor.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  int returned[4];
  for (int i = 0; i < 3; i++)
    returned[i] = wb_robot_step(time_step);
  wb_supervisor_simulation_quit(3);
  returned[3] = wb_robot_step(time_step);
  const char *dir = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  fprintf(out, "{\"returned\": [%d, %d, %d, %d], \"time\": %.6f}\n", returned[0], returned[1],
          returned[2], returned[3], wb_robot_get_time());
  fclose(out);
  wb_robot_cleanup();
  return 0;
}
