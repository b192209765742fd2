/* Webots' Pen functions (<webots/pen.h>; reference manual, Pen page). */
#ifndef WB_PEN_H
#define WB_PEN_H

#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

void wb_pen_write(WbDeviceTag tag, bool write);
void wb_pen_set_ink_color(WbDeviceTag tag, int color, double density);

#ifdef __cplusplus
}
#endif

#endif
