/* Webots' robot window functions (<webots/robot_wwi.h>): a headless run has no robot window,
   so texts sent are dropped and none is received (NULL). */
#ifndef WB_ROBOT_WWI_H
#define WB_ROBOT_WWI_H

#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

void wb_robot_wwi_send_text(const char *text);
const char *wb_robot_wwi_receive_text(void);

#ifdef __cplusplus
}
#endif

#endif
