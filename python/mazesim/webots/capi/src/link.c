/* The lockstep link to mazesim and Webots' robot functions (<webots/robot.h>). */
#include "link.h"

#include <errno.h>
#include <math.h>
#include <pthread.h>
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

Device *link_device(WbDeviceTag tag, const char *function) {
  link_start();
  if (tag == 0 || tag > link_robot.device_count) {
    fprintf(stderr, "Error: %s() called with an invalid device tag.\n", function);
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

int wb_robot_step(int duration) {
  link_start();
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

WbDeviceTag wb_robot_get_device(const char *name) {
  link_start();
  for (int i = 0; i < link_robot.device_count; i++)
    if (name && strcmp(link_robot.devices[i].name, name) == 0)
      return (WbDeviceTag)(i + 1);
  fprintf(stderr, "Device \"%s\" was not found on robot \"%s\"\n", name ? name : "(null)",
          link_robot.name);
  return 0;
}

int wb_robot_get_number_of_devices(void) {
  link_start();
  return link_robot.device_count;
}

WbDeviceTag wb_robot_get_device_by_index(int index) {
  link_start();
  if (index < 0 || index >= link_robot.device_count) {
    fprintf(stderr, "Error: wb_robot_get_device_by_index(): index %d out of range [0, %d).\n",
            index, link_robot.device_count);
    return 0;
  }
  return (WbDeviceTag)(index + 1);
}
