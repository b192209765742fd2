/* Webots' robot functions (<webots/robot.h>), implemented by mazesim's controller library. */
#ifndef WB_ROBOT_H
#define WB_ROBOT_H

#include <webots/nodes.h>
#include <webots/robot_wwi.h>
#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum { WB_MODE_SIMULATION = 0, WB_MODE_CROSS_COMPILATION, WB_MODE_REMOTE_CONTROL } WbRobotMode;
typedef enum {
  WB_EVENT_QUIT = -1,
  WB_EVENT_NO_EVENT = 0,
  WB_EVENT_MOUSE_CLICK = 1,
  WB_EVENT_MOUSE_MOVE = 2,
  WB_EVENT_KEYBOARD = 4,
  WB_EVENT_JOYSTICK_BUTTON = 8,
  WB_EVENT_JOYSTICK_AXIS = 16,
  WB_EVENT_JOYSTICK_POV = 32
} WbUserInputEvent;

int wb_robot_init(void);
void wb_robot_cleanup(void);
int wb_robot_step(int duration);
/* A step in two halves: here the first runs the whole step, the second answers its result. */
int wb_robot_step_begin(int duration);
int wb_robot_step_end(void);
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
WbNodeType wb_robot_get_type(void);
const char *wb_robot_get_urdf(const char *prefix);
/* The battery (a Robot node's battery field): read as the Python Robot reads it. */
void wb_robot_battery_sensor_enable(int sampling_period);
void wb_robot_battery_sensor_disable(void);
int wb_robot_battery_sensor_get_sampling_period(void);
double wb_robot_battery_sensor_get_value(void);
/* A headless run has no user: no event comes. */
WbUserInputEvent wb_robot_wait_for_user_input_event(WbUserInputEvent event_type, int timeout);
/* Webots' names before the Robot's data field became customData. */
const char *wb_robot_get_data(void);
void wb_robot_set_data(const char *data);
/* The keyboard functions of Webots 7 and before (now those of <webots/keyboard.h>). */
void wb_robot_keyboard_enable(int sampling_period);
void wb_robot_keyboard_disable(void);
int wb_robot_keyboard_get_key(void);

#ifdef __cplusplus
}
#endif

#endif
