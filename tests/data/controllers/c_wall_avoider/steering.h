/* The wall avoider's steering rule: wheel speeds from the front proximity sensors. */
#ifndef STEERING_H
#define STEERING_H

void steer(double left_front, double right_front, double *left_speed, double *right_speed);

#endif
