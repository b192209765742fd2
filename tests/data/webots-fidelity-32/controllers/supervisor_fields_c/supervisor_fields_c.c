/* Moves the robot DEF RUNNER through its translation field, reads the field and the node's
   position and velocity back, resets its physics, then resets the simulation and reads the
   field and the time again; writes what it read as JSON into
   $SWARM_LOG/supervisor_fields_c.json. */
#include <stdio.h>
#include <stdlib.h>
#include <webots/robot.h>
#include <webots/supervisor.h>

static void vector(FILE *out, const char *key, const double *v, int n) {
  fprintf(out, "\"%s\": [", key);
  for (int i = 0; i < n; i++)
    fprintf(out, "%s%.9g", i ? ", " : "", v[i]);
  fprintf(out, "]");
}

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  WbNodeRef runner = wb_supervisor_node_get_from_def("RUNNER");
  WbFieldRef translation = wb_supervisor_node_get_field(runner, "translation");
  double start[3], moved[3], position[3], driving[6], stopped[6], reset[3];
  const double *v = wb_supervisor_field_get_sf_vec3f(translation);
  for (int i = 0; i < 3; i++)
    start[i] = v[i];
  for (int i = 0; i < 5; i++)
    wb_robot_step(time_step);
  const double *w = wb_supervisor_node_get_velocity(runner);
  for (int i = 0; i < 6; i++)
    driving[i] = w[i];
  const double target[3] = {0.25, -0.3, 0.0};
  wb_supervisor_field_set_sf_vec3f(translation, target);
  wb_supervisor_node_reset_physics(runner);
  wb_robot_step(time_step);
  v = wb_supervisor_field_get_sf_vec3f(translation);
  for (int i = 0; i < 3; i++)
    moved[i] = v[i];
  const double *p = wb_supervisor_node_get_position(runner);
  for (int i = 0; i < 3; i++)
    position[i] = p[i];
  w = wb_supervisor_node_get_velocity(runner);
  for (int i = 0; i < 6; i++)
    stopped[i] = w[i];
  const double before_reset = wb_robot_get_time();
  wb_supervisor_simulation_reset();
  wb_robot_step(time_step);
  v = wb_supervisor_field_get_sf_vec3f(translation);
  for (int i = 0; i < 3; i++)
    reset[i] = v[i];
  const double after_reset = wb_robot_get_time();
  const char *dir = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  const char *keys[6] = {"start", "driving", "moved", "position", "stopped", "reset"};
  const double *values[6] = {start, driving, moved, position, stopped, reset};
  const int sizes[6] = {3, 6, 3, 3, 6, 3};
  fprintf(out, "{");
  for (int i = 0; i < 6; i++) {
    vector(out, keys[i], values[i], sizes[i]);
    fprintf(out, ", ");
  }
  fprintf(out, "\"before_reset\": %.6f, \"after_reset\": %.6f}\n", before_reset, after_reset);
  fclose(out);
  wb_robot_cleanup();
  return 0;
}
