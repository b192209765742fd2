/* Sets the e-puck's LEDs, a wheel's target and too high a velocity, reads them back and
   writes what it read as JSON into $SWARM_LOG/led_motor_c.json. */
#include <stdio.h>
#include <stdlib.h>
#include <webots/led.h>
#include <webots/motor.h>
#include <webots/robot.h>

int main(void) {
  wb_robot_init();
  const int time_step = (int)wb_robot_get_basic_time_step();
  char name[8];
  int values[10];
  WbDeviceTag leds[10];
  for (int i = 0; i < 10; i++) {
    snprintf(name, sizeof name, "led%d", i);
    leds[i] = wb_robot_get_device(name);
    wb_led_set(leds[i], i % 2);
  }
  WbDeviceTag right = wb_robot_get_device("right wheel motor");
  wb_motor_set_position(right, 2.0);
  wb_motor_set_velocity(right, 100.0);
  wb_robot_step(time_step);
  for (int i = 0; i < 10; i++)
    values[i] = wb_led_get(leds[i]);
  const char *dir = getenv("SWARM_LOG");
  char path[1024];
  snprintf(path, sizeof path, "%s/%s.json", dir ? dir : ".", wb_robot_get_name());
  FILE *out = fopen(path, "w");
  fprintf(out, "{\"leds\": [");
  for (int i = 0; i < 10; i++)
    fprintf(out, "%s%d", i ? ", " : "", values[i]);
  fprintf(out, "], \"target\": %g, \"velocity\": %g}\n", wb_motor_get_target_position(right),
          wb_motor_get_velocity(right));
  fclose(out);
  wb_robot_cleanup();
  return 0;
}
