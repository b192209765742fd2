/* Webots' Mouse functions (<webots/mouse.h>; reference manual, Mouse page). */
#ifndef WB_MOUSE_H
#define WB_MOUSE_H

#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  bool left;
  bool middle;
  bool right;
  double u;
  double v;
  double x;
  double y;
  double z;
} WbMouseState;

void wb_mouse_enable(int sampling_period);
void wb_mouse_disable(void);
int wb_mouse_get_sampling_period(void);
void wb_mouse_enable_3d_position(void);
void wb_mouse_disable_3d_position(void);
bool wb_mouse_is_3d_position_enabled(void);
WbMouseState wb_mouse_get_state(void);

#ifdef __cplusplus
}
#endif

#endif
