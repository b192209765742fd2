/*
 * After its 20th step, reads each robot's velocity (DEF S1 to S3) with
 * wb_supervisor_node_get_velocity, its rotation field and its orientation matrix.
 */
#include <stdio.h>
#include <stdlib.h>

#include <webots/robot.h>
#include <webots/supervisor.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  for (int i = 0; i < 20; i++)
    wb_robot_step(time_step);
  char path[1024];
  const char *dir = getenv("SWARM_LOG");
  snprintf(path, sizeof path, "%s/speedo.json", dir ? dir : ".");
  FILE *out = fopen(path, "w");
  if (!out)
    return 1;
  fprintf(out, "{");
  const char *defs[3] = {"S1", "S2", "S3"};
  for (int i = 0; i < 3; i++) {
    WbNodeRef node = wb_supervisor_node_get_from_def(defs[i]);
    const double *v = wb_supervisor_node_get_velocity(node);
    const double *r = wb_supervisor_field_get_sf_rotation(wb_supervisor_node_get_field(node, "rotation"));
    const double *m = wb_supervisor_node_get_orientation(node);
    fprintf(out, "%s\"%s\": {\"velocity\": [%.9g, %.9g, %.9g, %.9g, %.9g, %.9g], ", i ? ", " : "", defs[i], v[0],
            v[1], v[2], v[3], v[4], v[5]);
    fprintf(out, "\"rotation\": [%.9g, %.9g, %.9g, %.9g], \"heading\": [%.9g, %.9g]}", r[0], r[1], r[2], r[3], m[0],
            m[3]);
  }
  fprintf(out, ", \"time\": %.6f}\n", wb_robot_get_time());
  fclose(out);
  wb_robot_cleanup();
  return 0;
}
