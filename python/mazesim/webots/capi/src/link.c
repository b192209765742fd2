/* The lockstep link to mazesim and Webots' robot functions (<webots/robot.h>). */
#include "link.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <webots/robot.h>

Robot link_robot;

static int channel = -1;
/* Set once wb_robot_step has returned -1: the run is over. Webots then ends the controller
   itself, so a call the controller still makes (after its wb_robot_cleanup, say) ends it
   quietly, with status 0, instead of failing on the closed link. */
static int run_over;

typedef struct {
  int32_t op;
  int32_t tag;
  double a;
  double b;
} Command;

static Command *pending;
static int pending_count, pending_capacity;

void link_failed(const char *what) {
  fprintf(stderr, "mazesim controller library: %s; the controller stops\n", what);
  fflush(stderr);
  _exit(1);
}

static void send_all(const void *data, size_t size) {
  const char *bytes = data;
  while (size > 0) {
    ssize_t sent = write(channel, bytes, size);
    if (sent < 0 && errno == EINTR)
      continue;
    if (sent <= 0 && run_over)
      _exit(0);
    if (sent <= 0)
      link_failed("the link to mazesim is closed");
    bytes += sent;
    size -= (size_t)sent;
  }
}

static void receive_all(void *data, size_t size) {
  char *bytes = data;
  while (size > 0) {
    ssize_t got = read(channel, bytes, size);
    if (got < 0 && errno == EINTR)
      continue;
    if (got == 0)
      _exit(0); /* mazesim ended the run */
    if (got < 0)
      link_failed("reading from mazesim failed");
    bytes += got;
    size -= (size_t)got;
  }
}

static void *allocate(size_t size) {
  void *memory = calloc(1, size ? size : 1);
  if (!memory)
    link_failed("out of memory");
  return memory;
}

static int32_t receive_int(void) {
  int32_t value;
  receive_all(&value, sizeof value);
  return value;
}

static double receive_double(void) {
  double value;
  receive_all(&value, sizeof value);
  return value;
}

static char *receive_string(void) {
  int32_t size = receive_int();
  if (size < 0 || size > (1 << 20))
    link_failed("mazesim sent a malformed description");
  char *text = allocate((size_t)size + 1);
  receive_all(text, (size_t)size);
  return text;
}

static void send_int(int32_t value) {
  send_all(&value, sizeof value);
}

static void receive_description(void) {
  if (receive_int() != LINK_VERSION)
    link_failed("mazesim speaks another version of the link");
  link_robot.basic_time_step = receive_double();
  link_robot.time = receive_double();
  link_robot.name = receive_string();
  link_robot.model = receive_string();
  link_robot.custom_data = receive_string();
  link_robot.controller_name = receive_string();
  link_robot.project_path = receive_string();
  link_robot.world_path = receive_string();
  link_robot.supervisor = receive_int();
  link_robot.synchronization = receive_int();
  link_robot.device_count = receive_int();
  if (link_robot.device_count < 0 || link_robot.device_count > 65534)
    link_failed("mazesim sent a malformed description");
  link_robot.devices = allocate(sizeof(Device) * (size_t)link_robot.device_count);
  for (int i = 0; i < link_robot.device_count; i++) {
    Device *device = &link_robot.devices[i];
    device->name = receive_string();
    device->model = receive_string();
    device->node_type = (WbNodeType)receive_int();
    device->info_count = receive_int();
    if (device->info_count < 0 || device->info_count > 4096)
      link_failed("mazesim sent a malformed description");
    device->info = allocate(sizeof(double) * (size_t)device->info_count);
    for (int k = 0; k < device->info_count; k++)
      device->info[k] = receive_double();
    for (int k = 0; k < 3; k++)
      device->values[k] = NAN;
    device->set_point[0] = 0.0;
  }
}

void link_start(void) {
  if (link_robot.ready)
    return;
  if (run_over)
    _exit(0);
  const char *fd = getenv("MAZESIM_CONTROLLER_FD");
  if (!fd || !*fd)
    link_failed("MAZESIM_CONTROLLER_FD is not set: run this controller with `mazesim webots run`");
  channel = atoi(fd);
  /* Webots shows a controller's output line by line. */
  setvbuf(stdout, NULL, _IOLBF, 0);
  int32_t hello[2] = {LINK_HELLO, LINK_VERSION};
  send_all(hello, sizeof hello);
  receive_description();
  link_robot.ready = 1;
}

/* The link goes to the threads in the order they ask for it (a ticket each), so that a thread
   stepping in a loop cannot keep it from another. */
static pthread_mutex_t tickets = PTHREAD_MUTEX_INITIALIZER;
static pthread_cond_t turn = PTHREAD_COND_INITIALIZER;
static unsigned long next_ticket, serving;

void link_lock(void) {
  pthread_mutex_lock(&tickets);
  unsigned long ticket = next_ticket++;
  while (ticket != serving)
    pthread_cond_wait(&turn, &tickets);
  pthread_mutex_unlock(&tickets);
}

void link_unlock(void) {
  pthread_mutex_lock(&tickets);
  serving++;
  pthread_cond_broadcast(&turn);
  pthread_mutex_unlock(&tickets);
}

void link_command(int op, int tag, double a, double b) {
  link_start();
  link_lock();
  if (pending_count == pending_capacity) {
    pending_capacity = pending_capacity ? 2 * pending_capacity : 64;
    pending = realloc(pending, sizeof(Command) * (size_t)pending_capacity);
    if (!pending)
      link_failed("out of memory");
  }
  Command command = {op, tag, a, b};
  pending[pending_count++] = command;
  link_unlock();
}

void link_error(const char *function, const char *format, ...) {
  va_list arguments;
  va_start(arguments, format);
  fprintf(stderr, "Error: %s", function);
  vfprintf(stderr, format, arguments);
  fputc('\n', stderr);
  va_end(arguments);
}

/* The kinds of devices whose tags the functions of a prefix take; a function of no prefix here
   (wb_device_...) takes any device. */
static const struct {
  const char *prefix;
  WbNodeType types[2];
} kinds[] = {
  {"wb_accelerometer_", {WB_NODE_ACCELEROMETER}},
  {"wb_altimeter_", {WB_NODE_ALTIMETER}},
  {"wb_camera_", {WB_NODE_CAMERA}},
  {"wb_compass_", {WB_NODE_COMPASS}},
  {"wb_display_", {WB_NODE_DISPLAY}},
  {"wb_distance_sensor_", {WB_NODE_DISTANCE_SENSOR}},
  {"wb_emitter_", {WB_NODE_EMITTER}},
  {"wb_gps_", {WB_NODE_GPS}},
  {"wb_gyro_", {WB_NODE_GYRO}},
  {"wb_inertial_unit_", {WB_NODE_INERTIAL_UNIT}},
  {"wb_led_", {WB_NODE_LED}},
  {"wb_lidar_", {WB_NODE_LIDAR}},
  {"wb_light_sensor_", {WB_NODE_LIGHT_SENSOR}},
  {"wb_motor_", {WB_NODE_ROTATIONAL_MOTOR, WB_NODE_LINEAR_MOTOR}},
  {"wb_pen_", {WB_NODE_PEN}},
  {"wb_position_sensor_", {WB_NODE_POSITION_SENSOR}},
  {"wb_range_finder_", {WB_NODE_RANGE_FINDER}},
  {"wb_receiver_", {WB_NODE_RECEIVER}},
  {"wb_speaker_", {WB_NODE_SPEAKER}},
  {"wb_touch_sensor_", {WB_NODE_TOUCH_SENSOR}},
};

/* Whether `function` takes the tags of devices of `type`. */
static int takes(const char *function, WbNodeType type) {
  for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; i++)
    if (strncmp(function, kinds[i].prefix, strlen(kinds[i].prefix)) == 0)
      return type == kinds[i].types[0] || type == kinds[i].types[1];
  return 1;
}

Device *link_device(WbDeviceTag tag, const char *function) {
  link_start();
  /* Tag 0 is the robot itself, no device; a tag past the devices is none at all. */
  if (tag > link_robot.device_count)
    fprintf(stderr, "Error: device with tag=%d not found.\n", (int)tag);
  if (tag == 0 || tag > link_robot.device_count ||
      !takes(function, link_robot.devices[tag - 1].node_type)) {
    link_error(function, "(): invalid device tag.");
    return NULL;
  }
  return &link_robot.devices[tag - 1];
}

static void receive_readings(void) {
  int32_t count = receive_int();
  link_robot.key_count = 0;
  link_robot.key_next = 0;
  for (int32_t i = 0; i < count; i++) {
    int32_t tag = receive_int(), values = receive_int(), bytes = receive_int();
    if (values < 0 || values > 64 || bytes < 0 || bytes > (1 << 26) ||
        tag < 0 || tag > link_robot.device_count)
      link_failed("mazesim sent a malformed reading");
    double buffer[64];
    for (int k = 0; k < values; k++)
      buffer[k] = receive_double();
    if (tag == KEYBOARD_TAG) {
      for (int k = 0; k < values && k < 64; k++)
        link_robot.keys[link_robot.key_count++] = (int)buffer[k];
      continue;
    }
    Device *device = &link_robot.devices[tag - 1];
    device->value_count = values < 3 ? values : 3;
    for (int k = 0; k < device->value_count; k++)
      device->values[k] = buffer[k];
    if (bytes > 0) {
      if (bytes != device->image_size) {
        free(device->image);
        device->image = allocate((size_t)bytes);
        device->image_size = bytes;
      }
      receive_all(device->image, (size_t)bytes);
    }
  }
}

void link_send_with_commands(int kind, const void *message, size_t size) {
  link_start();
  int32_t header[2] = {kind, pending_count};
  send_all(header, sizeof header);
  if (pending_count)
    send_all(pending, sizeof(Command) * (size_t)pending_count);
  pending_count = 0;
  send_all(message, size);
}

void link_receive(void *data, size_t size) {
  receive_all(data, size);
}

int wb_robot_init(void) {
  link_start();
  return 1;
}

/* Webots' library sends the duration as an unsigned count of ms: a negative one asks for a step
   of 2^32 - |duration| ms, which outlasts any run (mazesim reads it so, see
   native_controller.py), without a message. */
int wb_robot_step(int duration) {
  link_start();
  /* Webots' library ends the controller at its first step after the one that returned -1
     (robot.c, WEBOTS_EXIT_NOW: exit(EXIT_SUCCESS)), so that one looping on without looking at
     -1 does not call on into a world whose run is over. */
  if (run_over)
    exit(EXIT_SUCCESS);
  link_lock();
  int32_t header[3] = {LINK_STEP, duration, pending_count};
  send_all(header, sizeof header);
  if (pending_count)
    send_all(pending, sizeof(Command) * (size_t)pending_count);
  pending_count = 0;
  int32_t result = receive_int();
  link_robot.time = receive_double();
  receive_readings();
  if (result == -1)
    run_over = 1;
  link_unlock();
  return result;
}

void wb_robot_cleanup(void) {
  if (!link_robot.ready)
    return;
  send_int(LINK_CLEANUP);
  fflush(NULL);
  close(channel);
  link_robot.ready = 0;
  channel = -1;
}

double wb_robot_get_basic_time_step(void) {
  link_start();
  return link_robot.basic_time_step;
}

double wb_robot_get_time(void) {
  link_start();
  return link_robot.time;
}

const char *wb_robot_get_name(void) {
  link_start();
  return link_robot.name;
}

const char *wb_robot_get_model(void) {
  link_start();
  return link_robot.model;
}

const char *wb_robot_get_custom_data(void) {
  link_start();
  return link_robot.custom_data;
}

void wb_robot_set_custom_data(const char *data) {
  link_start();
  size_t size = strlen(data ? data : "");
  char *copy = allocate(size + 1);
  memcpy(copy, data ? data : "", size);
  free(link_robot.custom_data);
  link_robot.custom_data = copy;
}

const char *wb_robot_get_controller_name(void) {
  link_start();
  return link_robot.controller_name;
}

const char *wb_robot_get_project_path(void) {
  link_start();
  return link_robot.project_path;
}

const char *wb_robot_get_world_path(void) {
  link_start();
  return link_robot.world_path;
}

bool wb_robot_get_supervisor(void) {
  link_start();
  return link_robot.supervisor != 0;
}

bool wb_robot_get_synchronization(void) {
  link_start();
  return link_robot.synchronization != 0;
}

WbRobotMode wb_robot_get_mode(void) {
  return WB_MODE_SIMULATION;
}

void wb_robot_set_mode(WbRobotMode mode, const char *argument) {
  (void)argument;
  if (mode != WB_MODE_SIMULATION)
    fprintf(stderr, "Error: wb_robot_set_mode(): mazesim simulates only (mode %d ignored).\n", mode);
}

/* How a message quotes a text of the controller's (a device name): at most 200 characters on
   one line, a control character as '?', "..." after a text cut short (a 10 MB name was written
   whole, over several lines). */
static const char *shown_text(const char *text) {
  static char shown[204];
  size_t n = 0;
  while (text[n] && n < 200) {
    unsigned char c = (unsigned char)text[n];
    shown[n] = (c < 0x20 || c == 0x7f) ? '?' : (char)c;
    n++;
  }
  if (text[n])
    memcpy(shown + n, "...", 3), n += 3;
  shown[n] = '\0';
  return shown;
}

WbDeviceTag wb_robot_get_device(const char *name) {
  if (!name || !name[0]) {
    link_error("wb_robot_get_device", "() called with NULL or empty argument.");
    return 0;
  }
  link_start();
  for (int i = 0; i < link_robot.device_count; i++)
    if (strcmp(link_robot.devices[i].name, name) == 0)
      return (WbDeviceTag)(i + 1);
  fprintf(stderr, "Warning: \"%s\" device not found.\n", shown_text(name));
  return 0;
}

int wb_robot_get_number_of_devices(void) {
  link_start();
  return link_robot.device_count;
}

WbDeviceTag wb_robot_get_device_by_index(int index) {
  link_start();
  if (index < 0 || index >= link_robot.device_count) {
    fprintf(stderr, "Error: The index of wb_robot_get_device_by_index() is out of the bounds.\n");
    return 0;
  }
  return (WbDeviceTag)(index + 1);
}
