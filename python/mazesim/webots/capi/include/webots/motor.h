/* Webots' motor functions (<webots/motor.h>): the e-puck's wheel motors. */
#ifndef WB_MOTOR_H
#define WB_MOTOR_H

#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif


void wb_motor_set_position(WbDeviceTag tag, double position);
void wb_motor_set_velocity(WbDeviceTag tag, double velocity);
void wb_motor_set_acceleration(WbDeviceTag tag, double acceleration);
void wb_motor_set_control_pid(WbDeviceTag tag, double p, double i, double d);
double wb_motor_get_target_position(WbDeviceTag tag);
double wb_motor_get_min_position(WbDeviceTag tag);
double wb_motor_get_max_position(WbDeviceTag tag);
double wb_motor_get_velocity(WbDeviceTag tag);
double wb_motor_get_max_velocity(WbDeviceTag tag);
double wb_motor_get_acceleration(WbDeviceTag tag);
WbJointType wb_motor_get_type(WbDeviceTag tag);
WbDeviceTag wb_motor_get_position_sensor(WbDeviceTag tag);

/* Torque (rotational motors) and force (linear motors), their feedback, coupling, brake. */
void wb_motor_set_available_torque(WbDeviceTag tag, double torque);
void wb_motor_set_available_force(WbDeviceTag tag, double force);
void wb_motor_set_torque(WbDeviceTag tag, double torque);
void wb_motor_set_force(WbDeviceTag tag, double force);
double wb_motor_get_available_torque(WbDeviceTag tag);
double wb_motor_get_available_force(WbDeviceTag tag);
double wb_motor_get_max_torque(WbDeviceTag tag);
double wb_motor_get_max_force(WbDeviceTag tag);
void wb_motor_enable_torque_feedback(WbDeviceTag tag, int sampling_period);
void wb_motor_enable_force_feedback(WbDeviceTag tag, int sampling_period);
void wb_motor_disable_torque_feedback(WbDeviceTag tag);
void wb_motor_disable_force_feedback(WbDeviceTag tag);
double wb_motor_get_torque_feedback(WbDeviceTag tag);
double wb_motor_get_force_feedback(WbDeviceTag tag);
int wb_motor_get_torque_feedback_sampling_period(WbDeviceTag tag);
int wb_motor_get_force_feedback_sampling_period(WbDeviceTag tag);
double wb_motor_get_multiplier(WbDeviceTag tag);
WbDeviceTag wb_motor_get_brake(WbDeviceTag tag);

#ifdef __cplusplus
}
#endif

#endif
