/* Walks the robot's devices by index, counts them by node type and checks that each is the
   device its name gives; writes what it found as JSON into $SWARM_LOG/device_walk_c.json. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <webots/device.h>
#include <webots/nodes.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  const int n = wb_robot_get_number_of_devices();
  int distance = 0, motors = 0, encoders = 0, leds = 0, cameras = 0, same = 0;
  for (int i = 0; i < n; i++) {
    WbDeviceTag tag = wb_robot_get_device_by_index(i);
    const char *name = wb_device_get_name(tag);
    if (wb_robot_get_device(name) == tag)
      same++;
    switch (wb_device_get_node_type(tag)) {
      case WB_NODE_DISTANCE_SENSOR: distance++; break;
      case WB_NODE_ROTATIONAL_MOTOR: motors++; break;
      case WB_NODE_POSITION_SENSOR: encoders++; break;
      case WB_NODE_LED: leds++; break;
      case WB_NODE_CAMERA: cameras++; break;
      default: break;
    }
  }
  wb_robot_step(time_step);
  const char *dir = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  fprintf(out,
          "{\"count\": %d, \"same\": %d, \"distance\": %d, \"motors\": %d, \"encoders\": %d, "
          "\"leds\": %d, \"cameras\": %d, \"time_step\": %d}\n",
          n, same, distance, motors, encoders, leds, cameras, time_step);
  fclose(out);
  wb_robot_cleanup();
  return 0;
}
