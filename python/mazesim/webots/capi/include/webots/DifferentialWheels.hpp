// Webots 8's C++ DifferentialWheels class (<webots/DifferentialWheels.hpp>), a Robot whose two
// wheels mazesim's C functions of <webots/differential_wheels.h> drive (speed units of 0.00628
// rad/s, encoders of 1/159.23 rad, as the e-puck's DifferentialWheels node had them).
#ifndef WB_DIFFERENTIAL_WHEELS_HPP
#define WB_DIFFERENTIAL_WHEELS_HPP

#include <webots/Robot.hpp>
#include <webots/differential_wheels.h>

namespace webots {
  class DifferentialWheels : public Robot {
  public:
    DifferentialWheels() {}
    virtual ~DifferentialWheels() {}
    virtual void setSpeed(double left, double right) {
      wb_differential_wheels_set_speed(left, right);
    }
    double getLeftSpeed() const { return wb_differential_wheels_get_left_speed(); }
    double getRightSpeed() const { return wb_differential_wheels_get_right_speed(); }
    double getMaxSpeed() const { return wb_differential_wheels_get_max_speed(); }
    double getSpeedUnit() const { return wb_differential_wheels_get_speed_unit(); }
    virtual void enableEncoders(int samplingPeriod) {
      wb_differential_wheels_enable_encoders(samplingPeriod);
    }
    virtual void disableEncoders() { wb_differential_wheels_disable_encoders(); }
    int getEncodersSamplingPeriod() const {
      return wb_differential_wheels_get_encoders_sampling_period();
    }
    double getLeftEncoder() const { return wb_differential_wheels_get_left_encoder(); }
    double getRightEncoder() const { return wb_differential_wheels_get_right_encoder(); }
    virtual void setEncoders(double left, double right) {
      wb_differential_wheels_set_encoders(left, right);
    }
  };
}  // namespace webots

#endif
