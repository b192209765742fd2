/* The wall avoider's steering rule (the same as wall_avoider_twin.py's). */
#include "steering.h"

#define CRUISE 5.0
#define NEAR 80.0

void steer(double left_front, double right_front, double *left_speed, double *right_speed) {
  *left_speed = CRUISE;
  *right_speed = CRUISE;
  if (left_front > NEAR)
    *right_speed = -CRUISE * 0.5;
  else if (right_front > NEAR)
    *left_speed = -CRUISE * 0.5;
  else {
    *left_speed += (left_front - right_front) * 0.01;
    *right_speed -= (left_front - right_front) * 0.01;
  }
}
