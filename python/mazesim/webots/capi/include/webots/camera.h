/* Webots' camera functions (<webots/camera.h>): images of 4 bytes a pixel, blue, green, red,
   alpha, row after row. */
#ifndef WB_CAMERA_H
#define WB_CAMERA_H

#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

void wb_camera_enable(WbDeviceTag tag, int sampling_period);
void wb_camera_disable(WbDeviceTag tag);
int wb_camera_get_sampling_period(WbDeviceTag tag);
const unsigned char *wb_camera_get_image(WbDeviceTag tag);
int wb_camera_get_width(WbDeviceTag tag);
int wb_camera_get_height(WbDeviceTag tag);
double wb_camera_get_fov(WbDeviceTag tag);
unsigned char wb_camera_image_get_red(const unsigned char *image, int width, int x, int y);
unsigned char wb_camera_image_get_green(const unsigned char *image, int width, int x, int y);
unsigned char wb_camera_image_get_blue(const unsigned char *image, int width, int x, int y);
unsigned char wb_camera_image_get_gray(const unsigned char *image, int width, int x, int y);
unsigned char wb_camera_image_get_grey(const unsigned char *image, int width, int x, int y);

#ifdef __cplusplus
}
#endif

#endif
