#include "steer.h"

#include <string.h>

double scout_speed(const char *name) {
  if (strcmp(name, "fast") == 0)
    return 5.0;
  if (strcmp(name, "slow") == 0)
    return 2.0;
  return 1.0;
}
