/* The DifferentialWheels functions of Webots 8 and older (<webots/differential_wheels.h>), on
   the e-puck's wheel motors and encoders: speeds in speed units of 0.00628 rad/s (1000 is the
   e-puck's top speed), encoders in steps of 1/159.23 rad. */
#ifndef WB_DIFFERENTIAL_WHEELS_H
#define WB_DIFFERENTIAL_WHEELS_H

#ifdef __cplusplus
extern "C" {
#endif

void wb_differential_wheels_set_speed(double left, double right);
double wb_differential_wheels_get_left_speed(void);
double wb_differential_wheels_get_right_speed(void);
double wb_differential_wheels_get_max_speed(void);
double wb_differential_wheels_get_speed_unit(void);
void wb_differential_wheels_enable_encoders(int sampling_period);
void wb_differential_wheels_disable_encoders(void);
int wb_differential_wheels_get_encoders_sampling_period(void);
double wb_differential_wheels_get_left_encoder(void);
double wb_differential_wheels_get_right_encoder(void);
void wb_differential_wheels_set_encoders(double left, double right);

#ifdef __cplusplus
}
#endif

#endif
