/* Webots' camera recognition object (<webots/camera_recognition_object.h>): an object a
   camera's Recognition node sees, with the fields Webots' reference manual documents. */
#ifndef WB_CAMERA_RECOGNITION_OBJECT_H
#define WB_CAMERA_RECOGNITION_OBJECT_H

typedef struct {
  int id;                   /* the object's node id */
  double position[3];       /* relative to the camera (m) */
  double orientation[4];    /* relative to the camera (axis-angle) */
  double size[2];           /* (m) */
  int position_on_image[2]; /* (pixels) */
  int size_on_image[2];     /* (pixels) */
  int number_of_colors;
  double *colors;           /* number_of_colors red, green, blue triples */
  char *model;
} WbCameraRecognitionObject;

#endif
