#ifndef STEER_H
#define STEER_H

/* The scouts' speed (rad/s) for the name their controllerArgs give, 1 for an unknown one. */
double scout_speed(const char *name);

#endif
