// The C++ device classes of Webots (<webots/Motor.hpp>, <webots/DistanceSensor.hpp>...) that
// mazesim implements, each forwarding to its device's C functions. Every class's own header
// includes this one.
#ifndef WB_DEVICES_HPP
#define WB_DEVICES_HPP

#include <webots/Device.hpp>
#include <webots/accelerometer.h>
#include <webots/camera.h>
#include <webots/compass.h>
#include <webots/distance_sensor.h>
#include <webots/gps.h>
#include <webots/gyro.h>
#include <webots/keyboard.h>
#include <webots/led.h>
#include <webots/light_sensor.h>
#include <webots/motor.h>
#include <webots/position_sensor.h>
#include <webots/touch_sensor.h>

// A sensor class: enable, disable, getSamplingPeriod and its reading `Method` (C's `function`).
#define MAZESIM_SENSOR(Class, prefix, Reading, Method, function)                                 \
  class Class : public Device {                                                                  \
  public:                                                                                        \
    explicit Class(WbDeviceTag tag) : Device(tag) {}                                             \
    explicit Class(const std::string &name) : Device(name) {}                                    \
    virtual void enable(int samplingPeriod) { prefix##_enable(tag, samplingPeriod); }            \
    virtual void disable() { prefix##_disable(tag); }                                            \
    int getSamplingPeriod() const { return prefix##_get_sampling_period(tag); }                  \
    Reading Method() const { return prefix##_##function(tag); }                                  \
    MAZESIM_##Class##_EXTRA                                                                      \
  };

#define MAZESIM_DistanceSensor_EXTRA                                                             \
  double getMinValue() const { return wb_distance_sensor_get_min_value(tag); }                   \
  double getMaxValue() const { return wb_distance_sensor_get_max_value(tag); }                   \
  double getAperture() const { return wb_distance_sensor_get_aperture(tag); }
#define MAZESIM_PositionSensor_EXTRA
#define MAZESIM_LightSensor_EXTRA
#define MAZESIM_TouchSensor_EXTRA
#define MAZESIM_GPS_EXTRA
#define MAZESIM_Compass_EXTRA
#define MAZESIM_Accelerometer_EXTRA
#define MAZESIM_Gyro_EXTRA
#define MAZESIM_Camera_EXTRA                                                                     \
  int getWidth() const { return wb_camera_get_width(tag); }                                      \
  int getHeight() const { return wb_camera_get_height(tag); }                                    \
  double getFov() const { return wb_camera_get_fov(tag); }                                       \
  static unsigned char imageGetRed(const unsigned char *image, int width, int x, int y) {        \
    return wb_camera_image_get_red(image, width, x, y);                                          \
  }                                                                                              \
  static unsigned char imageGetGreen(const unsigned char *image, int width, int x, int y) {      \
    return wb_camera_image_get_green(image, width, x, y);                                        \
  }                                                                                              \
  static unsigned char imageGetBlue(const unsigned char *image, int width, int x, int y) {       \
    return wb_camera_image_get_blue(image, width, x, y);                                         \
  }                                                                                              \
  static unsigned char imageGetGray(const unsigned char *image, int width, int x, int y) {       \
    return wb_camera_image_get_gray(image, width, x, y);                                         \
  }

namespace webots {
  MAZESIM_SENSOR(DistanceSensor, wb_distance_sensor, double, getValue, get_value)
  MAZESIM_SENSOR(PositionSensor, wb_position_sensor, double, getValue, get_value)
  MAZESIM_SENSOR(LightSensor, wb_light_sensor, double, getValue, get_value)
  MAZESIM_SENSOR(TouchSensor, wb_touch_sensor, double, getValue, get_value)
  MAZESIM_SENSOR(GPS, wb_gps, const double *, getValues, get_values)
  MAZESIM_SENSOR(Compass, wb_compass, const double *, getValues, get_values)
  MAZESIM_SENSOR(Accelerometer, wb_accelerometer, const double *, getValues, get_values)
  MAZESIM_SENSOR(Gyro, wb_gyro, const double *, getValues, get_values)
  MAZESIM_SENSOR(Camera, wb_camera, const unsigned char *, getImage, get_image)

  class Motor : public Device {
  public:
    enum Type { ROTATIONAL = WB_ROTATIONAL, LINEAR = WB_LINEAR };
    explicit Motor(WbDeviceTag tag) : Device(tag), sensor(0) {}
    explicit Motor(const std::string &name) : Device(name), sensor(0) {}
    virtual ~Motor() { delete sensor; }
    virtual void setPosition(double position) { wb_motor_set_position(tag, position); }
    virtual void setVelocity(double velocity) { wb_motor_set_velocity(tag, velocity); }
    virtual void setAcceleration(double value) { wb_motor_set_acceleration(tag, value); }
    double getTargetPosition() const { return wb_motor_get_target_position(tag); }
    double getMinPosition() const { return wb_motor_get_min_position(tag); }
    double getMaxPosition() const { return wb_motor_get_max_position(tag); }
    double getVelocity() const { return wb_motor_get_velocity(tag); }
    double getMaxVelocity() const { return wb_motor_get_max_velocity(tag); }
    double getAcceleration() const { return wb_motor_get_acceleration(tag); }
    Type getType() const { return static_cast<Type>(wb_motor_get_type(tag)); }
    PositionSensor *getPositionSensor() {
      if (!sensor)
        sensor = new PositionSensor(wb_motor_get_position_sensor(tag));
      return sensor;
    }

  private:
    PositionSensor *sensor;
  };

  class LED : public Device {
  public:
    explicit LED(WbDeviceTag tag) : Device(tag) {}
    explicit LED(const std::string &name) : Device(name) {}
    virtual void set(int value) { wb_led_set(tag, value); }
    int get() const { return wb_led_get(tag); }
  };

  class Keyboard {
  public:
    enum {
      END = WB_KEYBOARD_END,
      HOME = WB_KEYBOARD_HOME,
      LEFT = WB_KEYBOARD_LEFT,
      UP = WB_KEYBOARD_UP,
      RIGHT = WB_KEYBOARD_RIGHT,
      DOWN = WB_KEYBOARD_DOWN,
      PAGEUP = WB_KEYBOARD_PAGEUP,
      PAGEDOWN = WB_KEYBOARD_PAGEDOWN,
      NUMPAD_HOME = WB_KEYBOARD_NUMPAD_HOME,
      NUMPAD_LEFT = WB_KEYBOARD_NUMPAD_LEFT,
      NUMPAD_UP = WB_KEYBOARD_NUMPAD_UP,
      NUMPAD_RIGHT = WB_KEYBOARD_NUMPAD_RIGHT,
      NUMPAD_DOWN = WB_KEYBOARD_NUMPAD_DOWN,
      NUMPAD_END = WB_KEYBOARD_NUMPAD_END,
      KEY = WB_KEYBOARD_KEY,
      SHIFT = WB_KEYBOARD_SHIFT,
      CONTROL = WB_KEYBOARD_CONTROL,
      ALT = WB_KEYBOARD_ALT
    };
    virtual ~Keyboard() {}
    virtual void enable(int samplingPeriod) { wb_keyboard_enable(samplingPeriod); }
    virtual void disable() { wb_keyboard_disable(); }
    int getSamplingPeriod() const { return wb_keyboard_get_sampling_period(); }
    int getKey() const { return wb_keyboard_get_key(); }
  };
}  // namespace webots

#undef MAZESIM_SENSOR
#endif
