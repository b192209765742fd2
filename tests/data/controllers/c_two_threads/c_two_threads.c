/* Steps 40 times in its main thread while a second thread reads the camera's exposure (a call
   over the link) without pause. Prints whether the second thread read, whether any of its reads
   was wrong, and whether the steps all ran. */
#include <pthread.h>
#include <sched.h>
#include <stdio.h>

#include <webots/camera.h>
#include <webots/robot.h>

static volatile int stepping = 1;
static volatile int reads;
static int wrong;

static void *reader(void *camera) {
  while (stepping) {
    if (wb_camera_get_exposure(*(WbDeviceTag *)camera) != 1.0)
      wrong++;
    reads++;
  }
  return NULL;
}

int main(void) {
  wb_robot_init();
  int step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag camera = wb_robot_get_device("camera");
  pthread_t thread;
  pthread_create(&thread, NULL, reader, &camera);
  /* On a loaded machine the second thread may not run before the 40 steps end: wait for its
     first read, after which it keeps reading while the main thread steps. */
  while (!reads)
    sched_yield();
  int steps = 0;
  while (steps < 40 && wb_robot_step(step) != -1)
    steps++;
  stepping = 0;
  pthread_join(thread, NULL);
  printf("read %d wrong %d steps %d time %.3f\n", reads > 0, wrong, steps, wb_robot_get_time());
  wb_robot_cleanup();
  return 0;
}
