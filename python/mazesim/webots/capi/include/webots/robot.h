/* Webots' robot functions (<webots/robot.h>), implemented by mazesim's controller library. */
#ifndef WB_ROBOT_H
#define WB_ROBOT_H

#include <webots/nodes.h>
#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { WB_MODE_SIMULATION = 0, WB_MODE_CROSS_COMPILATION, WB_MODE_REMOTE_CONTROL } WbRobotMode;

int wb_robot_init(void);
void wb_robot_cleanup(void);
int wb_robot_step(int duration);
double wb_robot_get_basic_time_step(void);
double wb_robot_get_time(void);
const char *wb_robot_get_name(void);
const char *wb_robot_get_model(void);
const char *wb_robot_get_custom_data(void);
void wb_robot_set_custom_data(const char *data);
const char *wb_robot_get_controller_name(void);
const char *wb_robot_get_project_path(void);
const char *wb_robot_get_world_path(void);
bool wb_robot_get_supervisor(void);
bool wb_robot_get_synchronization(void);
WbRobotMode wb_robot_get_mode(void);
void wb_robot_set_mode(WbRobotMode mode, const char *argument);
WbDeviceTag wb_robot_get_device(const char *name);
int wb_robot_get_number_of_devices(void);
WbDeviceTag wb_robot_get_device_by_index(int index);
/* The keyboard functions of Webots 7 and before (now those of <webots/keyboard.h>). */
void wb_robot_keyboard_enable(int sampling_period);
void wb_robot_keyboard_disable(void);
int wb_robot_keyboard_get_key(void);

#ifdef __cplusplus
}
#endif

#endif
