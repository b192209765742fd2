/* The C twin of tests/data/controllers/supervisor_teleport.py: a supervisor moves its own
   robot, reads it back, drives and quits the simulation with status 3. */
#include <math.h>
#include <stdio.h>

#include <webots/motor.h>
#include <webots/robot.h>
#include <webots/supervisor.h>

static void print_vector(const char *label, const double *values, int count) {
  printf("%s", label);
  for (int i = 0; i < count; i++)
    printf(" %.17g", values[i]);
  printf("\n");
}

int main(void) {
  wb_robot_init();
  int time_step = (int)wb_robot_get_basic_time_step();
  WbNodeRef robot = wb_supervisor_node_get_from_def("EPUCK");
  if (!robot)
    robot = wb_supervisor_node_get_self();
  WbFieldRef translation = wb_supervisor_node_get_field(robot, "translation");
  WbFieldRef rotation = wb_supervisor_node_get_field(robot, "rotation");
  print_vector("start", wb_supervisor_field_get_sf_vec3f(translation), 3);
  print_vector("rotation", wb_supervisor_field_get_sf_rotation(rotation), 4);
  const double position[3] = {0.2, -0.1, 0.0}, heading[4] = {0, 0, 1, 1.5708};
  wb_supervisor_field_set_sf_vec3f(translation, position);
  wb_supervisor_field_set_sf_rotation(rotation, heading);
  wb_robot_step(time_step);
  print_vector("moved", wb_supervisor_node_get_position(robot), 3);
  WbDeviceTag left = wb_robot_get_device("left wheel motor");
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(left, INFINITY);
  wb_motor_set_position(right, INFINITY);
  wb_motor_set_velocity(left, 3.0);
  wb_motor_set_velocity(right, 3.0);
  while (wb_robot_step(time_step) != -1) {
    if (wb_robot_get_time() > 1.0) {
      print_vector("velocity", wb_supervisor_node_get_velocity(robot), 6);
      wb_supervisor_simulation_quit(3);
    }
  }
  wb_robot_cleanup();
  return 0;
}
