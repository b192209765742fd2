/*
 * A C supervisor that finds the e-pucks A0..A9 by their DEF names and, after its last step,
 * writes every one's wb_supervisor_node_get_position and the first column of its orientation,
 * and its translation field.
 */
#include <stdio.h>
#include <stdlib.h>

#include <webots/robot.h>
#include <webots/supervisor.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbNodeRef nodes[10];
  char def[8];
  for (int i = 0; i < 10; i++) {
    snprintf(def, sizeof def, "A%d", i);
    nodes[i] = wb_supervisor_node_get_from_def(def);
  }
  int steps = 0;
  while (wb_robot_step(time_step) != -1 && steps < 300)
    steps++;
  char path[1024];
  const char *dir = getenv("SWARM_LOG");
  snprintf(path, sizeof path, "%s/census.json", dir ? dir : ".");
  FILE *out = fopen(path, "w");
  if (!out)
    return 1;
  fprintf(out, "{\"steps\": %d, \"robots\": [", steps);
  for (int i = 0; i < 10; i++) {
    const double *p = wb_supervisor_node_get_position(nodes[i]);
    const double *r = wb_supervisor_node_get_orientation(nodes[i]);
    const double *t =
      wb_supervisor_field_get_sf_vec3f(wb_supervisor_node_get_field(nodes[i], "translation"));
    fprintf(out, "%s[%.9g, %.9g, %.9g, %.9g, %.9g, %.9g, %.9g]", i ? ", " : "", p[0], p[1], p[2],
            r[0], r[3], t[0], t[1]);
  }
  fprintf(out, "]}\n");
  fclose(out);
  wb_robot_cleanup();
  return 0;
}
