/* Webots' Display functions (reference manual, Display page): mazesim has no view to draw on,
   so drawings are accepted and dropped and images hold their size only (see display.h). */
#include <stdlib.h>

#include <webots/display.h>

#include "link.h"

struct WbImageStructPrivate {
  int width;
  int height;
};

/* The display of a tag, or NULL after Webots' message naming `function`. */
static Device *display(WbDeviceTag tag, const char *function) {
  return link_device(tag, function);
}

/* A display's fixed fact `index` (its width, then its height; see native_link.py). */
static int fact(WbDeviceTag tag, int index, const char *function) {
  Device *device = display(tag, function);
  return device && index < device->info_count ? (int)device->info[index] : 0;
}

int wb_display_get_width(WbDeviceTag tag) {
  return fact(tag, 0, "wb_display_get_width");
}

int wb_display_get_height(WbDeviceTag tag) {
  return fact(tag, 1, "wb_display_get_height");
}

void wb_display_set_color(WbDeviceTag tag, int color) {
  (void)color;
  display(tag, "wb_display_set_color");
}

void wb_display_set_alpha(WbDeviceTag tag, double alpha) {
  (void)alpha;
  display(tag, "wb_display_set_alpha");
}

void wb_display_set_opacity(WbDeviceTag tag, double opacity) {
  (void)opacity;
  display(tag, "wb_display_set_opacity");
}

void wb_display_set_font(WbDeviceTag tag, const char *font, int size, bool anti_aliasing) {
  (void)font, (void)size, (void)anti_aliasing;
  display(tag, "wb_display_set_font");
}

void wb_display_attach_camera(WbDeviceTag tag, WbDeviceTag camera_tag) {
  (void)camera_tag;
  display(tag, "wb_display_attach_camera");
}

void wb_display_detach_camera(WbDeviceTag tag) {
  display(tag, "wb_display_detach_camera");
}

void wb_display_draw_pixel(WbDeviceTag tag, int x, int y) {
  (void)x, (void)y;
  display(tag, "wb_display_draw_pixel");
}

void wb_display_draw_line(WbDeviceTag tag, int x1, int y1, int x2, int y2) {
  (void)x1, (void)y1, (void)x2, (void)y2;
  display(tag, "wb_display_draw_line");
}

void wb_display_draw_rectangle(WbDeviceTag tag, int x, int y, int width, int height) {
  (void)x, (void)y, (void)width, (void)height;
  display(tag, "wb_display_draw_rectangle");
}

void wb_display_draw_oval(WbDeviceTag tag, int cx, int cy, int a, int b) {
  (void)cx, (void)cy, (void)a, (void)b;
  display(tag, "wb_display_draw_oval");
}

void wb_display_draw_polygon(WbDeviceTag tag, const int *x, const int *y, int size) {
  (void)x, (void)y, (void)size;
  display(tag, "wb_display_draw_polygon");
}

void wb_display_draw_text(WbDeviceTag tag, const char *text, int x, int y) {
  (void)text, (void)x, (void)y;
  display(tag, "wb_display_draw_text");
}

void wb_display_fill_rectangle(WbDeviceTag tag, int x, int y, int width, int height) {
  (void)x, (void)y, (void)width, (void)height;
  display(tag, "wb_display_fill_rectangle");
}

void wb_display_fill_oval(WbDeviceTag tag, int cx, int cy, int a, int b) {
  (void)cx, (void)cy, (void)a, (void)b;
  display(tag, "wb_display_fill_oval");
}

void wb_display_fill_polygon(WbDeviceTag tag, const int *x, const int *y, int size) {
  (void)x, (void)y, (void)size;
  display(tag, "wb_display_fill_polygon");
}

static WbImageRef image(int width, int height) {
  WbImageRef made = malloc(sizeof *made);
  if (!made)
    link_failed("out of memory");
  made->width = width > 0 ? width : 0;
  made->height = height > 0 ? height : 0;
  return made;
}

WbImageRef wb_display_image_new(WbDeviceTag tag, int width, int height, const void *data,
                                int format) {
  (void)data, (void)format;
  return display(tag, "wb_display_image_new") ? image(width, height) : NULL;
}

WbImageRef wb_display_image_load(WbDeviceTag tag, const char *filename) {
  (void)filename;
  return display(tag, "wb_display_image_load") ? image(0, 0) : NULL;
}

WbImageRef wb_display_image_copy(WbDeviceTag tag, int x, int y, int width, int height) {
  (void)x, (void)y;
  return display(tag, "wb_display_image_copy") ? image(width, height) : NULL;
}

void wb_display_image_paste(WbDeviceTag tag, WbImageRef ir, int x, int y, bool blend) {
  (void)ir, (void)x, (void)y, (void)blend;
  display(tag, "wb_display_image_paste");
}

void wb_display_image_save(WbDeviceTag tag, WbImageRef ir, const char *filename) {
  (void)ir, (void)filename;
  display(tag, "wb_display_image_save");
}

void wb_display_image_delete(WbDeviceTag tag, WbImageRef ir) {
  if (display(tag, "wb_display_image_delete"))
    free(ir);
}
