// Webots' C++ Robot class (<webots/Robot.hpp>), over mazesim's C library: getDevice gives the
// device of its node type (a Motor*, a DistanceSensor*...), made once and owned by the robot.
#ifndef WB_ROBOT_HPP
#define WB_ROBOT_HPP

#include <cstdlib>
#include <iostream>
#include <map>
#include <string>

#include <webots/Devices.hpp>
#include <webots/robot.h>

namespace webots {
  class Robot {
  public:
    // As Webots' Robot.cpp: a second Robot (or Supervisor) ends the controller, status 255.
    Robot() {
      if (instance()) {
        std::cerr << "Only one instance of the Robot class should be created" << std::endl;
        wb_robot_cleanup();
        exit(-1);
      }
      instance() = this;
      wb_robot_init();
    }
    virtual ~Robot() {
      typedef std::map<WbDeviceTag, Device *>::iterator Owned;
      for (Owned i = ownDevices.begin(); i != ownDevices.end(); ++i)
        delete i->second;
      wb_robot_cleanup();
    }
    virtual int step(int duration) { return wb_robot_step(duration); }
    double getBasicTimeStep() const { return wb_robot_get_basic_time_step(); }
    double getTime() const { return wb_robot_get_time(); }
    std::string getName() const { return wb_robot_get_name(); }
    std::string getModel() const { return wb_robot_get_model(); }
    std::string getCustomData() const { return wb_robot_get_custom_data(); }
    void setCustomData(const std::string &data) { wb_robot_set_custom_data(data.c_str()); }
    std::string getData() const { return wb_robot_get_data(); }
    void setData(const std::string &data) { wb_robot_set_data(data.c_str()); }
    bool getSupervisor() const { return wb_robot_get_supervisor(); }
    bool getSynchronization() const { return wb_robot_get_synchronization(); }
    std::string getControllerName() const { return wb_robot_get_controller_name(); }
    std::string getProjectPath() const { return wb_robot_get_project_path(); }
    std::string getWorldPath() const { return wb_robot_get_world_path(); }
    void setMode(int mode, const char *argument) {
      wb_robot_set_mode(static_cast<WbRobotMode>(mode), argument);
    }
    int getType() const { return wb_robot_get_type(); }
    std::string getUrdf(const std::string &prefix = "") const {
      const char *urdf = wb_robot_get_urdf(prefix.c_str());
      return urdf ? urdf : "";
    }
    virtual int stepBegin(int duration) { return wb_robot_step_begin(duration); }
    virtual int stepEnd() { return wb_robot_step_end(); }
    enum UserInputEvent {
      EVENT_QUIT = WB_EVENT_QUIT,
      EVENT_NO_EVENT = WB_EVENT_NO_EVENT,
      EVENT_MOUSE_CLICK = WB_EVENT_MOUSE_CLICK,
      EVENT_MOUSE_MOVE = WB_EVENT_MOUSE_MOVE,
      EVENT_KEYBOARD = WB_EVENT_KEYBOARD,
      EVENT_JOYSTICK_BUTTON = WB_EVENT_JOYSTICK_BUTTON,
      EVENT_JOYSTICK_AXIS = WB_EVENT_JOYSTICK_AXIS,
      EVENT_JOYSTICK_POV = WB_EVENT_JOYSTICK_POV
    };
    UserInputEvent waitForUserInputEvent(UserInputEvent eventType, int timeout) {
      return static_cast<UserInputEvent>(
        wb_robot_wait_for_user_input_event(static_cast<WbUserInputEvent>(eventType), timeout));
    }
    void wwiSendText(const std::string &text) { wb_robot_wwi_send_text(text.c_str()); }
    std::string wwiReceiveText() {
      const char *text = wb_robot_wwi_receive_text();
      return text ? text : "";
    }
    virtual void batterySensorEnable(int samplingPeriod) {
      wb_robot_battery_sensor_enable(samplingPeriod);
    }
    virtual void batterySensorDisable() { wb_robot_battery_sensor_disable(); }
    int batterySensorGetSamplingPeriod() const {
      return wb_robot_battery_sensor_get_sampling_period();
    }
    double batterySensorGetValue() const { return wb_robot_battery_sensor_get_value(); }
    // The keyboard functions of Webots 7 and before.
    void keyboardEnable(int samplingPeriod) { wb_robot_keyboard_enable(samplingPeriod); }
    void keyboardDisable() { wb_robot_keyboard_disable(); }
    int keyboardGetKey() const { return wb_robot_keyboard_get_key(); }
    int getMode() const { return wb_robot_get_mode(); }
    int getNumberOfDevices() const { return wb_robot_get_number_of_devices(); }
    Device *getDeviceByIndex(int index) { return device(wb_robot_get_device_by_index(index)); }
    Device *getDevice(const std::string &name) { return device(wb_robot_get_device(name.c_str())); }
    Keyboard *getKeyboard() { return &ownKeyboard; }
    Mouse *getMouse() { return &ownMouse; }
    Joystick *getJoystick() { return &ownJoystick; }
    Motor *getMotor(const std::string &name) { return dynamic_cast<Motor *>(getDevice(name)); }
    DistanceSensor *getDistanceSensor(const std::string &name) {
      return dynamic_cast<DistanceSensor *>(getDevice(name));
    }
    PositionSensor *getPositionSensor(const std::string &name) {
      return dynamic_cast<PositionSensor *>(getDevice(name));
    }
    LightSensor *getLightSensor(const std::string &name) {
      return dynamic_cast<LightSensor *>(getDevice(name));
    }
    TouchSensor *getTouchSensor(const std::string &name) {
      return dynamic_cast<TouchSensor *>(getDevice(name));
    }
    LED *getLED(const std::string &name) { return dynamic_cast<LED *>(getDevice(name)); }
    GPS *getGPS(const std::string &name) { return dynamic_cast<GPS *>(getDevice(name)); }
    Compass *getCompass(const std::string &name) { return dynamic_cast<Compass *>(getDevice(name)); }
    Accelerometer *getAccelerometer(const std::string &name) {
      return dynamic_cast<Accelerometer *>(getDevice(name));
    }
    Gyro *getGyro(const std::string &name) { return dynamic_cast<Gyro *>(getDevice(name)); }
    InertialUnit *getInertialUnit(const std::string &name) {
      return dynamic_cast<InertialUnit *>(getDevice(name));
    }
    Lidar *getLidar(const std::string &name) { return dynamic_cast<Lidar *>(getDevice(name)); }
    Camera *getCamera(const std::string &name) { return dynamic_cast<Camera *>(getDevice(name)); }
    Emitter *getEmitter(const std::string &name) {
      return dynamic_cast<Emitter *>(getDevice(name));
    }
    Receiver *getReceiver(const std::string &name) {
      return dynamic_cast<Receiver *>(getDevice(name));
    }
    Display *getDisplay(const std::string &name) {
      return dynamic_cast<Display *>(getDevice(name));
    }
    Pen *getPen(const std::string &name) { return dynamic_cast<Pen *>(getDevice(name)); }
    Speaker *getSpeaker(const std::string &name) {
      return dynamic_cast<Speaker *>(getDevice(name));
    }
    Altimeter *getAltimeter(const std::string &name) {
      return dynamic_cast<Altimeter *>(getDevice(name));
    }
    RangeFinder *getRangeFinder(const std::string &name) {
      return dynamic_cast<RangeFinder *>(getDevice(name));
    }
    Radar *getRadar(const std::string &name) { return dynamic_cast<Radar *>(getDevice(name)); }
    Brake *getBrake(const std::string &name) { return dynamic_cast<Brake *>(getDevice(name)); }
    Connector *getConnector(const std::string &name) {
      return dynamic_cast<Connector *>(getDevice(name));
    }
    Skin *getSkin(const std::string &name) { return dynamic_cast<Skin *>(getDevice(name)); }
    VacuumGripper *getVacuumGripper(const std::string &name) {
      return dynamic_cast<VacuumGripper *>(getDevice(name));
    }

  private:
    // The first Robot made (one for the whole program, the header's functions being inline).
    static Robot *&instance() {
      static Robot *first = 0;
      return first;
    }
    Device *device(WbDeviceTag tag) {
      if (!tag)
        return 0;
      std::map<WbDeviceTag, Device *>::iterator found = ownDevices.find(tag);
      if (found != ownDevices.end())
        return found->second;
      Device *made = make(tag);
      ownDevices[tag] = made;
      return made;
    }
    static Device *make(WbDeviceTag tag) {
      switch (wb_device_get_node_type(tag)) {
        case WB_NODE_ROTATIONAL_MOTOR:
        case WB_NODE_LINEAR_MOTOR:
          return new Motor(tag);
        case WB_NODE_DISTANCE_SENSOR:
          return new DistanceSensor(tag);
        case WB_NODE_POSITION_SENSOR:
          return new PositionSensor(tag);
        case WB_NODE_LIGHT_SENSOR:
          return new LightSensor(tag);
        case WB_NODE_TOUCH_SENSOR:
          return new TouchSensor(tag);
        case WB_NODE_LED:
          return new LED(tag);
        case WB_NODE_GPS:
          return new GPS(tag);
        case WB_NODE_COMPASS:
          return new Compass(tag);
        case WB_NODE_ACCELEROMETER:
          return new Accelerometer(tag);
        case WB_NODE_GYRO:
          return new Gyro(tag);
        case WB_NODE_INERTIAL_UNIT:
          return new InertialUnit(tag);
        case WB_NODE_LIDAR:
          return new Lidar(tag);
        case WB_NODE_CAMERA:
          return new Camera(tag);
        case WB_NODE_EMITTER:
          return new Emitter(tag);
        case WB_NODE_RECEIVER:
          return new Receiver(tag);
        case WB_NODE_DISPLAY:
          return new Display(tag);
        case WB_NODE_PEN:
          return new Pen(tag);
        case WB_NODE_SPEAKER:
          return new Speaker(tag);
        case WB_NODE_ALTIMETER:
          return new Altimeter(tag);
        case WB_NODE_RANGE_FINDER:
          return new RangeFinder(tag);
        case WB_NODE_RADAR:
          return new Radar(tag);
        case WB_NODE_BRAKE:
          return new Brake(tag);
        case WB_NODE_CONNECTOR:
          return new Connector(tag);
        case WB_NODE_SKIN:
          return new Skin(tag);
        case WB_NODE_VACUUM_GRIPPER:
          return new VacuumGripper(tag);
        default:
          return new Device(tag);
      }
    }
    std::map<WbDeviceTag, Device *> ownDevices;
    Keyboard ownKeyboard;
    Mouse ownMouse;
    Joystick ownJoystick;
  };
}  // namespace webots

#endif
