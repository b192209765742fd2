// The C++ device classes of Webots (<webots/Motor.hpp>, <webots/DistanceSensor.hpp>...) that
// mazesim implements, each forwarding to its device's C functions. Every class's own header
// includes this one.
#ifndef WB_DEVICES_HPP
#define WB_DEVICES_HPP

#include <map>
#include <string>

#include <webots/Device.hpp>
#include <webots/accelerometer.h>
#include <webots/altimeter.h>
#include <webots/brake.h>
#include <webots/camera.h>
#include <webots/compass.h>
#include <webots/connector.h>
#include <webots/display.h>
#include <webots/distance_sensor.h>
#include <webots/emitter.h>
#include <webots/gps.h>
#include <webots/gyro.h>
#include <webots/inertial_unit.h>
#include <webots/joystick.h>
#include <webots/keyboard.h>
#include <webots/led.h>
#include <webots/lidar.h>
#include <webots/light_sensor.h>
#include <webots/motor.h>
#include <webots/mouse.h>
#include <webots/pen.h>
#include <webots/position_sensor.h>
#include <webots/radar.h>
#include <webots/range_finder.h>
#include <webots/receiver.h>
#include <webots/skin.h>
#include <webots/speaker.h>
#include <webots/touch_sensor.h>
#include <webots/vacuum_gripper.h>

// A sensor's lookup table (rows of input, output, noise) as Webots' C++ classes give it.
#define MAZESIM_LOOKUP_TABLE(prefix)                                                              \
  const double *getLookupTable() const { return prefix##_get_lookup_table(tag); }               \
  int getLookupTableSize() const { return prefix##_get_lookup_table_size(tag); }

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
  double getAperture() const { return wb_distance_sensor_get_aperture(tag); }                   \
  enum Type { GENERIC = WB_DISTANCE_SENSOR_GENERIC, INFRA_RED = WB_DISTANCE_SENSOR_INFRA_RED,     \
              SONAR = WB_DISTANCE_SENSOR_SONAR, LASER = WB_DISTANCE_SENSOR_LASER };              \
  Type getType() const { return static_cast<Type>(wb_distance_sensor_get_type(tag)); }           \
  MAZESIM_LOOKUP_TABLE(wb_distance_sensor)
#define MAZESIM_PositionSensor_EXTRA                                                             \
  enum { ROTATIONAL = WB_ROTATIONAL, LINEAR = WB_LINEAR };                                       \
  int getType() const { return wb_position_sensor_get_type(tag); }                               \
  WbDeviceTag getMotorTag() const { return wb_position_sensor_get_motor(tag); }                  \
  WbDeviceTag getBrakeTag() const { return wb_position_sensor_get_brake(tag); }                  \
  Motor *getMotor() const;                                                                       \
  /* mazesim has no C++ Brake class: a brake's tag is getBrakeTag's (0, none, on the e-puck). */ \
  Device *getBrake() const { return 0; }
#define MAZESIM_LightSensor_EXTRA MAZESIM_LOOKUP_TABLE(wb_light_sensor)
#define MAZESIM_TouchSensor_EXTRA                                                                \
  enum Type { BUMPER = WB_TOUCH_SENSOR_BUMPER, FORCE = WB_TOUCH_SENSOR_FORCE,                    \
              FORCE3D = WB_TOUCH_SENSOR_FORCE3D };                                               \
  const double *getValues() const { return wb_touch_sensor_get_values(tag); }                    \
  Type getType() const { return static_cast<Type>(wb_touch_sensor_get_type(tag)); }              \
  MAZESIM_LOOKUP_TABLE(wb_touch_sensor)
#define MAZESIM_GPS_EXTRA                                                                        \
  enum CoordinateSystem { LOCAL = WB_GPS_LOCAL_COORDINATE, WGS84 = WB_GPS_WGS84_COORDINATE };    \
  double getSpeed() const { return wb_gps_get_speed(tag); }                                      \
  const double *getSpeedVector() const { return wb_gps_get_speed_vector(tag); }                  \
  CoordinateSystem getCoordinateSystem() const {                                                 \
    return static_cast<CoordinateSystem>(wb_gps_get_coordinate_system(tag));                     \
  }                                                                                              \
  static std::string convertToDegreesMinutesSeconds(double decimalDegree) {                      \
    return wb_gps_convert_to_degrees_minutes_seconds(decimalDegree);                             \
  }
#define MAZESIM_Compass_EXTRA MAZESIM_LOOKUP_TABLE(wb_compass)
#define MAZESIM_Accelerometer_EXTRA MAZESIM_LOOKUP_TABLE(wb_accelerometer)
#define MAZESIM_Gyro_EXTRA MAZESIM_LOOKUP_TABLE(wb_gyro)
#define MAZESIM_Altimeter_EXTRA
#define MAZESIM_Radar_EXTRA                                                                      \
  int getNumberOfTargets() const { return wb_radar_get_number_of_targets(tag); }                 \
  double getMinRange() const { return wb_radar_get_min_range(tag); }                             \
  double getMaxRange() const { return wb_radar_get_max_range(tag); }                             \
  double getHorizontalFov() const { return wb_radar_get_horizontal_fov(tag); }                   \
  double getVerticalFov() const { return wb_radar_get_vertical_fov(tag); }
#define MAZESIM_RangeFinder_EXTRA                                                                \
  int getWidth() const { return wb_range_finder_get_width(tag); }                                \
  int getHeight() const { return wb_range_finder_get_height(tag); }                              \
  double getFov() const { return wb_range_finder_get_fov(tag); }                                 \
  double getMinRange() const { return wb_range_finder_get_min_range(tag); }                      \
  double getMaxRange() const { return wb_range_finder_get_max_range(tag); }                      \
  static float rangeImageGetDepth(const float *image, int width, int x, int y) {                 \
    return wb_range_finder_image_get_depth(image, width, x, y);                                  \
  }
#define MAZESIM_InertialUnit_EXTRA                                                               \
  const double *getQuaternion() const { return wb_inertial_unit_get_quaternion(tag); }           \
  double getNoise() const { return wb_inertial_unit_get_noise(tag); }
#define MAZESIM_Lidar_EXTRA                                                                      \
  virtual void enablePointCloud() { wb_lidar_enable_point_cloud(tag); }                          \
  virtual void disablePointCloud() { wb_lidar_disable_point_cloud(tag); }                        \
  bool isPointCloudEnabled() const { return wb_lidar_is_point_cloud_enabled(tag); }              \
  const float *getLayerRangeImage(int layer) const {                                             \
    return wb_lidar_get_layer_range_image(tag, layer);                                           \
  }                                                                                              \
  const LidarPoint *getPointCloud() const { return wb_lidar_get_point_cloud(tag); }              \
  const LidarPoint *getLayerPointCloud(int layer) const {                                        \
    return wb_lidar_get_layer_point_cloud(tag, layer);                                           \
  }                                                                                              \
  int getNumberOfPoints() const { return wb_lidar_get_number_of_points(tag); }                   \
  int getHorizontalResolution() const { return wb_lidar_get_horizontal_resolution(tag); }        \
  int getNumberOfLayers() const { return wb_lidar_get_number_of_layers(tag); }                   \
  double getMinFrequency() const { return wb_lidar_get_min_frequency(tag); }                     \
  double getMaxFrequency() const { return wb_lidar_get_max_frequency(tag); }                     \
  double getFrequency() const { return wb_lidar_get_frequency(tag); }                            \
  virtual void setFrequency(double frequency) { wb_lidar_set_frequency(tag, frequency); }        \
  double getFov() const { return wb_lidar_get_fov(tag); }                                        \
  double getVerticalFov() const { return wb_lidar_get_vertical_fov(tag); }                       \
  double getMinRange() const { return wb_lidar_get_min_range(tag); }                             \
  double getMaxRange() const { return wb_lidar_get_max_range(tag); }
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
  }                                                                                              \
  static unsigned char imageGetGrey(const unsigned char *image, int width, int x, int y) {       \
    return wb_camera_image_get_grey(image, width, x, y);                                         \
  }                                                                                              \
  virtual void setFov(double fov) { wb_camera_set_fov(tag, fov); }                               \
  double getMinFov() const { return wb_camera_get_min_fov(tag); }                                \
  double getMaxFov() const { return wb_camera_get_max_fov(tag); }                                \
  double getExposure() const { return wb_camera_get_exposure(tag); }                             \
  virtual void setExposure(double exposure) { wb_camera_set_exposure(tag, exposure); }           \
  double getFocalLength() const { return wb_camera_get_focal_length(tag); }                      \
  double getFocalDistance() const { return wb_camera_get_focal_distance(tag); }                  \
  double getMinFocalDistance() const { return wb_camera_get_min_focal_distance(tag); }           \
  double getMaxFocalDistance() const { return wb_camera_get_max_focal_distance(tag); }           \
  virtual void setFocalDistance(double distance) { wb_camera_set_focal_distance(tag, distance); } \
  double getNear() const { return wb_camera_get_near(tag); }                                     \
  int saveImage(const std::string &filename, int quality) const {                                \
    return wb_camera_save_image(tag, filename.c_str(), quality);                                 \
  }                                                                                              \
  int saveRecognitionSegmentationImage(const std::string &filename, int quality) const {         \
    return wb_camera_recognition_save_segmentation_image(tag, filename.c_str(), quality);        \
  }                                                                                              \
  bool hasRecognition() const { return wb_camera_has_recognition(tag); }                         \
  void recognitionEnable(int samplingPeriod) {                                                   \
    wb_camera_recognition_enable(tag, samplingPeriod);                                           \
  }                                                                                              \
  void recognitionDisable() { wb_camera_recognition_disable(tag); }                              \
  int getRecognitionSamplingPeriod() const {                                                     \
    return wb_camera_recognition_get_sampling_period(tag);                                       \
  }                                                                                              \
  int getRecognitionNumberOfObjects() const {                                                    \
    return wb_camera_recognition_get_number_of_objects(tag);                                     \
  }                                                                                              \
  const CameraRecognitionObject *getRecognitionObjects() const {                                 \
    return wb_camera_recognition_get_objects(tag);                                               \
  }                                                                                              \
  bool hasRecognitionSegmentation() const {                                                      \
    return wb_camera_recognition_has_segmentation(tag);                                          \
  }                                                                                              \
  void enableRecognitionSegmentation() { wb_camera_recognition_enable_segmentation(tag); }       \
  void disableRecognitionSegmentation() { wb_camera_recognition_disable_segmentation(tag); }     \
  bool isRecognitionSegmentationEnabled() const {                                                \
    return wb_camera_recognition_is_segmentation_enabled(tag);                                   \
  }                                                                                              \
  const unsigned char *getRecognitionSegmentationImage() const {                                 \
    return wb_camera_recognition_get_segmentation_image(tag);                                    \
  }

namespace webots {
  class Motor;
  // Webots' C++ recognition object is its C struct.
  typedef WbCameraRecognitionObject CameraRecognitionObject;
  // And its lidar point is its C struct.
  typedef WbLidarPoint LidarPoint;
  MAZESIM_SENSOR(DistanceSensor, wb_distance_sensor, double, getValue, get_value)
  MAZESIM_SENSOR(PositionSensor, wb_position_sensor, double, getValue, get_value)
  MAZESIM_SENSOR(LightSensor, wb_light_sensor, double, getValue, get_value)
  MAZESIM_SENSOR(TouchSensor, wb_touch_sensor, double, getValue, get_value)
  MAZESIM_SENSOR(GPS, wb_gps, const double *, getValues, get_values)
  MAZESIM_SENSOR(Compass, wb_compass, const double *, getValues, get_values)
  MAZESIM_SENSOR(Accelerometer, wb_accelerometer, const double *, getValues, get_values)
  MAZESIM_SENSOR(Gyro, wb_gyro, const double *, getValues, get_values)
  MAZESIM_SENSOR(InertialUnit, wb_inertial_unit, const double *, getRollPitchYaw,
                 get_roll_pitch_yaw)
  MAZESIM_SENSOR(Lidar, wb_lidar, const float *, getRangeImage, get_range_image)
  MAZESIM_SENSOR(Camera, wb_camera, const unsigned char *, getImage, get_image)
  MAZESIM_SENSOR(Altimeter, wb_altimeter, double, getValue, get_value)
  MAZESIM_SENSOR(RangeFinder, wb_range_finder, const float *, getRangeImage, get_range_image)
  MAZESIM_SENSOR(Radar, wb_radar, const WbRadarTarget *, getTargets, get_targets)

  class Motor : public Device {
  public:
    enum Type { ROTATIONAL = WB_ROTATIONAL, LINEAR = WB_LINEAR };
    explicit Motor(WbDeviceTag tag) : Device(tag), sensor(0) {}
    explicit Motor(const std::string &name) : Device(name), sensor(0) {}
    virtual ~Motor() { delete sensor; }
    virtual void setPosition(double position) { wb_motor_set_position(tag, position); }
    virtual void setVelocity(double velocity) { wb_motor_set_velocity(tag, velocity); }
    virtual void setAcceleration(double value) { wb_motor_set_acceleration(tag, value); }
    virtual void setControlPID(double p, double i, double d) {
      wb_motor_set_control_pid(tag, p, i, d);
    }
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
    virtual void setAvailableTorque(double torque) { wb_motor_set_available_torque(tag, torque); }
    virtual void setAvailableForce(double force) { wb_motor_set_available_force(tag, force); }
    virtual void setTorque(double torque) { wb_motor_set_torque(tag, torque); }
    virtual void setForce(double force) { wb_motor_set_force(tag, force); }
    double getAvailableTorque() const { return wb_motor_get_available_torque(tag); }
    double getAvailableForce() const { return wb_motor_get_available_force(tag); }
    double getMaxTorque() const { return wb_motor_get_max_torque(tag); }
    double getMaxForce() const { return wb_motor_get_max_force(tag); }
    virtual void enableTorqueFeedback(int samplingPeriod) {
      wb_motor_enable_torque_feedback(tag, samplingPeriod);
    }
    virtual void enableForceFeedback(int samplingPeriod) {
      wb_motor_enable_force_feedback(tag, samplingPeriod);
    }
    virtual void disableTorqueFeedback() { wb_motor_disable_torque_feedback(tag); }
    virtual void disableForceFeedback() { wb_motor_disable_force_feedback(tag); }
    double getTorqueFeedback() const { return wb_motor_get_torque_feedback(tag); }
    double getForceFeedback() const { return wb_motor_get_force_feedback(tag); }
    int getTorqueFeedbackSamplingPeriod() const {
      return wb_motor_get_torque_feedback_sampling_period(tag);
    }
    int getForceFeedbackSamplingPeriod() const {
      return wb_motor_get_force_feedback_sampling_period(tag);
    }
    double getMultiplier() const { return wb_motor_get_multiplier(tag); }
    WbDeviceTag getBrakeTag() const { return wb_motor_get_brake(tag); }
    // mazesim has no C++ Brake class: a brake's tag is getBrakeTag's (0, none, on the e-puck).
    Device *getBrake() const { return 0; }

  private:
    PositionSensor *sensor;
  };

  // A position sensor's motor, made once per motor.
  inline Motor *PositionSensor::getMotor() const {
    static std::map<WbDeviceTag, Motor *> motors;
    WbDeviceTag motor = getMotorTag();
    if (!motor)
      return 0;
    if (!motors[motor])
      motors[motor] = new Motor(motor);
    return motors[motor];
  }

  class LED : public Device {
  public:
    explicit LED(WbDeviceTag tag) : Device(tag) {}
    explicit LED(const std::string &name) : Device(name) {}
    virtual void set(int value) { wb_led_set(tag, value); }
    int get() const { return wb_led_get(tag); }
  };

  // A pen and a speaker: nothing is drawn or heard (see their C functions).
  class Pen : public Device {
  public:
    explicit Pen(WbDeviceTag tag) : Device(tag) {}
    explicit Pen(const std::string &name) : Device(name) {}
    virtual void write(bool write) { wb_pen_write(tag, write); }
    virtual void setInkColor(int color, double density) {
      wb_pen_set_ink_color(tag, color, density);
    }
  };

  class Speaker : public Device {
  public:
    explicit Speaker(WbDeviceTag tag) : Device(tag) {}
    explicit Speaker(const std::string &name) : Device(name) {}
    static void playSound(Speaker *left, Speaker *right, const std::string &sound, double volume,
                          double pitch, double balance, bool loop) {
      wb_speaker_play_sound(left ? left->getTag() : 0, right ? right->getTag() : 0,
                            sound.c_str(), volume, pitch, balance, loop);
    }
    void stop(const std::string &sound) { wb_speaker_stop(tag, sound.c_str()); }
    bool isSoundPlaying(const std::string &sound) const {
      return wb_speaker_is_sound_playing(tag, sound.c_str());
    }
    bool setEngine(const std::string &engine) { return wb_speaker_set_engine(tag, engine.c_str()); }
    bool setLanguage(const std::string &language) {
      return wb_speaker_set_language(tag, language.c_str());
    }
    std::string getEngine() const { return text(wb_speaker_get_engine(tag)); }
    std::string getLanguage() const { return text(wb_speaker_get_language(tag)); }
    void speak(const std::string &text, double volume) {
      wb_speaker_speak(tag, text.c_str(), volume);
    }
    bool isSpeaking() const { return wb_speaker_is_speaking(tag); }
  };

  // Devices mazesim's robots never carry: their tags are refused (see absent_devices.c).
  class Brake : public Device {
  public:
    enum { ROTATIONAL = WB_ROTATIONAL, LINEAR = WB_LINEAR };
    explicit Brake(WbDeviceTag tag) : Device(tag) {}
    explicit Brake(const std::string &name) : Device(name) {}
    virtual void setDampingConstant(double dampingConstant) const {
      wb_brake_set_damping_constant(tag, dampingConstant);
    }
    int getType() const { return wb_brake_get_type(tag); }
    WbDeviceTag getMotorTag() const { return wb_brake_get_motor(tag); }
    WbDeviceTag getPositionSensorTag() const { return wb_brake_get_position_sensor(tag); }
  };

  class Connector : public Device {
  public:
    explicit Connector(WbDeviceTag tag) : Device(tag) {}
    explicit Connector(const std::string &name) : Device(name) {}
    virtual void enablePresence(int samplingPeriod) {
      wb_connector_enable_presence(tag, samplingPeriod);
    }
    virtual void disablePresence() { wb_connector_disable_presence(tag); }
    int getPresenceSamplingPeriod() const {
      return wb_connector_get_presence_sampling_period(tag);
    }
    int getPresence() const { return wb_connector_get_presence(tag); }
    virtual void lock() { wb_connector_lock(tag); }
    virtual void unlock() { wb_connector_unlock(tag); }
    bool isLocked() const { return wb_connector_is_locked(tag); }
  };

  class Skin : public Device {
  public:
    explicit Skin(WbDeviceTag tag) : Device(tag) {}
    explicit Skin(const std::string &name) : Device(name) {}
    void setBoneOrientation(int index, const double orientation[4], bool absolute) {
      wb_skin_set_bone_orientation(tag, index, orientation, absolute);
    }
    void setBonePosition(int index, const double position[3], bool absolute) {
      wb_skin_set_bone_position(tag, index, position, absolute);
    }
    int getBoneCount() const { return wb_skin_get_bone_count(tag); }
    std::string getBoneName(int index) const { return text(wb_skin_get_bone_name(tag, index)); }
    const double *getBoneOrientation(int index, bool absolute) const {
      return wb_skin_get_bone_orientation(tag, index, absolute);
    }
    const double *getBonePosition(int index, bool absolute) const {
      return wb_skin_get_bone_position(tag, index, absolute);
    }
  };

  class VacuumGripper : public Device {
  public:
    explicit VacuumGripper(WbDeviceTag tag) : Device(tag) {}
    explicit VacuumGripper(const std::string &name) : Device(name) {}
    virtual void enablePresence(int samplingPeriod) {
      wb_vacuum_gripper_enable_presence(tag, samplingPeriod);
    }
    virtual void disablePresence() { wb_vacuum_gripper_disable_presence(tag); }
    int getPresenceSamplingPeriod() const {
      return wb_vacuum_gripper_get_presence_sampling_period(tag);
    }
    bool getPresence() const { return wb_vacuum_gripper_get_presence(tag); }
    virtual void turnOn() { wb_vacuum_gripper_turn_on(tag); }
    virtual void turnOff() { wb_vacuum_gripper_turn_off(tag); }
    bool isOn() const { return wb_vacuum_gripper_is_on(tag); }
  };

  // The radio (reference manual, Emitter and Receiver pages).
  class Emitter : public Device {
  public:
    enum { CHANNEL_BROADCAST = WB_CHANNEL_BROADCAST };
    explicit Emitter(WbDeviceTag tag) : Device(tag) {}
    explicit Emitter(const std::string &name) : Device(name) {}
    virtual int send(const void *data, int size) { return wb_emitter_send(tag, data, size); }
    int getBufferSize() const { return wb_emitter_get_buffer_size(tag); }
    virtual void setChannel(int channel) { wb_emitter_set_channel(tag, channel); }
    int getChannel() const { return wb_emitter_get_channel(tag); }
    double getRange() const { return wb_emitter_get_range(tag); }
    virtual void setRange(double range) { wb_emitter_set_range(tag, range); }
  };

  class Receiver : public Device {
  public:
    enum { CHANNEL_BROADCAST = WB_CHANNEL_BROADCAST };
    explicit Receiver(WbDeviceTag tag) : Device(tag) {}
    explicit Receiver(const std::string &name) : Device(name) {}
    virtual void enable(int samplingPeriod) { wb_receiver_enable(tag, samplingPeriod); }
    virtual void disable() { wb_receiver_disable(tag); }
    int getSamplingPeriod() const { return wb_receiver_get_sampling_period(tag); }
    int getQueueLength() const { return wb_receiver_get_queue_length(tag); }
    virtual void nextPacket() { wb_receiver_next_packet(tag); }
    const void *getData() const { return wb_receiver_get_data(tag); }
    std::string getString() const { return text(wb_receiver_get_string(tag)); }
    int getDataSize() const { return wb_receiver_get_data_size(tag); }
    double getSignalStrength() const { return wb_receiver_get_signal_strength(tag); }
    const double *getEmitterDirection() const { return wb_receiver_get_emitter_direction(tag); }
    virtual void setChannel(int channel) { wb_receiver_set_channel(tag, channel); }
    int getChannel() const { return wb_receiver_get_channel(tag); }
  };

  // A display whose drawings are accepted and not drawn (see <webots/display.h>).
  class ImageRef {
  public:
    explicit ImageRef(WbImageRef image) : image(image) {}
    WbImageRef getImageRef() const { return image; }

  private:
    WbImageRef image;
  };

  class Display : public Device {
  public:
    enum { RGB = WB_IMAGE_RGB, RGBA = WB_IMAGE_RGBA, ARGB = WB_IMAGE_ARGB, BGRA = WB_IMAGE_BGRA,
           ABGR = WB_IMAGE_ABGR };
    explicit Display(WbDeviceTag tag) : Device(tag) {}
    explicit Display(const std::string &name) : Device(name) {}
    int getWidth() const { return wb_display_get_width(tag); }
    int getHeight() const { return wb_display_get_height(tag); }
    virtual void setColor(int color) { wb_display_set_color(tag, color); }
    virtual void setAlpha(double alpha) { wb_display_set_alpha(tag, alpha); }
    virtual void setOpacity(double opacity) { wb_display_set_opacity(tag, opacity); }
    virtual void setFont(const std::string &font, int size, bool antiAliasing) {
      wb_display_set_font(tag, font.c_str(), size, antiAliasing);
    }
    void attachCamera(Device *camera) { wb_display_attach_camera(tag, camera->getTag()); }
    void detachCamera() { wb_display_detach_camera(tag); }
    virtual void drawPixel(int x, int y) { wb_display_draw_pixel(tag, x, y); }
    virtual void drawLine(int x1, int y1, int x2, int y2) {
      wb_display_draw_line(tag, x1, y1, x2, y2);
    }
    virtual void drawRectangle(int x, int y, int width, int height) {
      wb_display_draw_rectangle(tag, x, y, width, height);
    }
    virtual void drawOval(int cx, int cy, int a, int b) { wb_display_draw_oval(tag, cx, cy, a, b); }
    virtual void drawPolygon(const int *x, const int *y, int size) {
      wb_display_draw_polygon(tag, x, y, size);
    }
    virtual void drawText(const std::string &text, int x, int y) {
      wb_display_draw_text(tag, text.c_str(), x, y);
    }
    virtual void fillRectangle(int x, int y, int width, int height) {
      wb_display_fill_rectangle(tag, x, y, width, height);
    }
    virtual void fillOval(int cx, int cy, int a, int b) { wb_display_fill_oval(tag, cx, cy, a, b); }
    virtual void fillPolygon(const int *x, const int *y, int size) {
      wb_display_fill_polygon(tag, x, y, size);
    }
    ImageRef *imageNew(int width, int height, const void *data, int format) const {
      return new ImageRef(wb_display_image_new(tag, width, height, data, format));
    }
    ImageRef *imageLoad(const std::string &filename) const {
      return new ImageRef(wb_display_image_load(tag, filename.c_str()));
    }
    ImageRef *imageCopy(int x, int y, int width, int height) const {
      return new ImageRef(wb_display_image_copy(tag, x, y, width, height));
    }
    virtual void imagePaste(ImageRef *ir, int x, int y, bool blend = false) {
      wb_display_image_paste(tag, ir ? ir->getImageRef() : 0, x, y, blend);
    }
    void imageSave(ImageRef *ir, const std::string &filename) const {
      wb_display_image_save(tag, ir ? ir->getImageRef() : 0, filename.c_str());
    }
    void imageDelete(ImageRef *ir) const {
      if (ir)
        wb_display_image_delete(tag, ir->getImageRef());
      delete ir;
    }
  };

  // The headless run's mouse (no button, the pointer outside the view) and no joystick.
  class Mouse {
  public:
    virtual ~Mouse() {}
    virtual void enable(int samplingPeriod) { wb_mouse_enable(samplingPeriod); }
    virtual void disable() { wb_mouse_disable(); }
    int getSamplingPeriod() const { return wb_mouse_get_sampling_period(); }
    void enable3dPosition() { wb_mouse_enable_3d_position(); }
    void disable3dPosition() { wb_mouse_disable_3d_position(); }
    bool is3dPositionEnabled() const { return wb_mouse_is_3d_position_enabled(); }
    const WbMouseState getState() const { return wb_mouse_get_state(); }
  };

  class Joystick {
  public:
    virtual ~Joystick() {}
    virtual void enable(int samplingPeriod) { wb_joystick_enable(samplingPeriod); }
    virtual void disable() { wb_joystick_disable(); }
    int getSamplingPeriod() const { return wb_joystick_get_sampling_period(); }
    bool isConnected() const { return wb_joystick_is_connected(); }
    std::string getModel() const {
      const char *model = wb_joystick_get_model();
      return model ? model : "";
    }
    int getNumberOfAxes() const { return wb_joystick_get_number_of_axes(); }
    int getAxisValue(int axis) const { return wb_joystick_get_axis_value(axis); }
    int getNumberOfPovs() const { return wb_joystick_get_number_of_povs(); }
    int getPovValue(int pov) const { return wb_joystick_get_pov_value(pov); }
    int getPressedButton() const { return wb_joystick_get_pressed_button(); }
    void setConstantForce(int level) { wb_joystick_set_constant_force(level); }
    void setConstantForceDuration(double duration) {
      wb_joystick_set_constant_force_duration(duration);
    }
    void setAutoCenteringGain(double gain) { wb_joystick_set_auto_centering_gain(gain); }
    void setResistanceGain(double gain) { wb_joystick_set_resistance_gain(gain); }
    void setForceAxis(int axis) { wb_joystick_set_force_axis(axis); }
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
