/* Steps in its main thread while a second thread reads the camera's exposure without pause,
   until one of its reads comes while the main thread is inside wb_robot_step (the library
   refuses it: NaN). Prints the steps, the time and whether a read was refused. */
#include <math.h>
#include <pthread.h>
#include <stdio.h>

#include <webots/camera.h>
#include <webots/robot.h>

static volatile int refused;

static void *reader(void *camera) {
  while (!refused) {
    if (isnan(wb_camera_get_exposure(*(WbDeviceTag *)camera)))
      refused = 1;
  }
  return NULL;
}

int main(void) {
  wb_robot_init();
  int step = (int)wb_robot_get_basic_time_step();
  WbDeviceTag camera = wb_robot_get_device("camera");
  pthread_t thread;
  pthread_create(&thread, NULL, reader, &camera);
  int steps = 0;
  while (!refused && wb_robot_step(step) != -1)
    steps++;
  pthread_join(thread, NULL);
  /* The link is whole: the steps all ran and the main thread's own reads are answered. */
  printf("refused %d steps match %d exposure %.1f\n", refused,
         fabs(wb_robot_get_time() - steps * step / 1000.0) < 1e-9,
         wb_camera_get_exposure(camera));
  wb_robot_cleanup();
  return 0;
}
