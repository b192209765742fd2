/* The controller's side of mazesim's lockstep link (see mazesim/webots/native_link.py for the
   protocol): the robot's description, the commands waiting for the next step, and the readings
   of the last one. */
#ifndef MAZESIM_LINK_H
#define MAZESIM_LINK_H

#include <stddef.h>

#include <webots/camera_recognition_object.h>
#include <webots/lidar.h>
#include <webots/nodes.h>
#include <webots/types.h>

/* The protocol's version; both ends check it. */
#define LINK_VERSION 4

/* What the controller sends. */
enum { LINK_HELLO = 1, LINK_STEP = 2, LINK_CLEANUP = 3, LINK_CALL = 4 };

/* The commands a step carries. */
enum {
  COMMAND_ENABLE = 1,
  COMMAND_DISABLE = 2,
  COMMAND_SET_POSITION = 3,
  COMMAND_SET_VELOCITY = 4,
  COMMAND_SET_ACCELERATION = 5,
  COMMAND_LED_SET = 6
};

/* The tag that stands for the keyboard in enable commands and readings. */
#define KEYBOARD_TAG 0

typedef struct {
  char *name;
  char *model;
  WbNodeType node_type;
  int info_count;
  double *info;           /* fixed facts of the device, by node type (see native_link.py) */
  int sampling_period;    /* ms, 0 when disabled */
  int value_count;
  double values[3];       /* the last reading */
  int image_size;
  unsigned char *image;   /* a camera's image, as fetched at `image_time` */
  double image_time;
  double set_point[3];    /* a motor's target position, velocity and acceleration */
  int led;
  unsigned char *packet;  /* a receiver's head packet, as the last wb_receiver_get_data read it */
  double direction[3];    /* a receiver's head packet's emitter direction */
  int object_count;       /* a camera's recognised objects, as fetched at `objects_time` */
  WbCameraRecognitionObject *objects;
  double objects_time;
  double quaternion[4];   /* an inertial unit's orientation, as the last call read it */
  int range_count;        /* a lidar's range image and point cloud, as the last calls read them */
  float *ranges;
  int point_count;
  WbLidarPoint *points;
} Device;

typedef struct {
  int ready;
  double basic_time_step;
  double time;
  char *name;
  char *model;
  char *custom_data;
  char *controller_name;
  char *project_path;
  char *world_path;
  int supervisor;
  int synchronization;
  int device_count;
  Device *devices;
  int keyboard_period;
  int key_count;
  int key_next;
  int keys[64];
} Robot;

extern Robot link_robot;

/* Prints why the controller cannot go on and exits. */
void link_failed(const char *what);
/* Connects on first use (wb_robot_init does, and any call made before it). */
void link_start(void);
/* Queues a command for the next step. */
void link_command(int op, int tag, double a, double b);
/* Sends the commands queued so far and `size` bytes of a message after them, unanswered yet
   (the caller holds the link). */
void link_send_with_commands(int kind, const void *message, size_t size);
/* Reads `size` bytes of mazesim's answer. */
void link_receive(void *data, size_t size);
/* The library serves its threads one at a time, in the order they ask: a thread holds the link
   for a whole step, a whole call (from sending it to reading its answer) or queueing a command,
   and another thread wanting the link meanwhile waits. */
void link_lock(void);
void link_unlock(void);

/* Most bytes a value of a call carries (MAX_VALUE_BYTES in native_link.py). */
#define LINK_MAX_VALUE_BYTES (1 << 26)

/* Prints Webots' message for a refused argument or use: "Error: ", the function's name, then
   the rest as printf formats it. The caller returns what Webots' function returns after such a
   message, and the controller goes on. */
void link_error(const char *function, const char *format, ...)
  __attribute__((format(printf, 2, 3)));

/* The device of a tag, or NULL after printing Webots' message naming `function`. As in Webots,
   a function of one kind of device (named wb_motor_..., wb_camera_...) refuses the tags of the
   other kinds. */
Device *link_device(WbDeviceTag tag, const char *function);

#endif
