/* Webots' Brake, Connector, Radar, Skin and VacuumGripper functions. mazesim's robots carry none
   of these devices (the Python module's classes are inert, and a world's are not built), so
   every tag is refused with Webots' message and the functions answer what Webots answers for no
   device: a controller that includes their headers builds, and one that looks for such a device
   finds none, as its Python twin does. */
#include <math.h>
#include <stddef.h>

#include <webots/brake.h>
#include <webots/connector.h>
#include <webots/radar.h>
#include <webots/skin.h>
#include <webots/vacuum_gripper.h>

#include "link.h"

/* Prints Webots' message for a tag that is no device of this kind. */
static void refused(const char *function) {
  link_start();
  link_error(function, "(): invalid device tag.");
}

void wb_brake_set_damping_constant(WbDeviceTag tag, double damping_constant) {
  (void)tag, (void)damping_constant;
  refused("wb_brake_set_damping_constant");
}

WbJointType wb_brake_get_type(WbDeviceTag tag) {
  (void)tag;
  refused("wb_brake_get_type");
  return WB_ROTATIONAL;
}

WbDeviceTag wb_brake_get_motor(WbDeviceTag tag) {
  (void)tag;
  refused("wb_brake_get_motor");
  return 0;
}

WbDeviceTag wb_brake_get_position_sensor(WbDeviceTag tag) {
  (void)tag;
  refused("wb_brake_get_position_sensor");
  return 0;
}

void wb_connector_enable_presence(WbDeviceTag tag, int sampling_period) {
  (void)tag, (void)sampling_period;
  refused("wb_connector_enable_presence");
}

void wb_connector_disable_presence(WbDeviceTag tag) {
  (void)tag;
  refused("wb_connector_disable_presence");
}

int wb_connector_get_presence_sampling_period(WbDeviceTag tag) {
  (void)tag;
  refused("wb_connector_get_presence_sampling_period");
  return 0;
}

int wb_connector_get_presence(WbDeviceTag tag) {
  (void)tag;
  refused("wb_connector_get_presence");
  return -1;
}

void wb_connector_lock(WbDeviceTag tag) {
  (void)tag;
  refused("wb_connector_lock");
}

void wb_connector_unlock(WbDeviceTag tag) {
  (void)tag;
  refused("wb_connector_unlock");
}

bool wb_connector_is_locked(WbDeviceTag tag) {
  (void)tag;
  refused("wb_connector_is_locked");
  return false;
}

void wb_radar_enable(WbDeviceTag tag, int sampling_period) {
  (void)tag, (void)sampling_period;
  refused("wb_radar_enable");
}

void wb_radar_disable(WbDeviceTag tag) {
  (void)tag;
  refused("wb_radar_disable");
}

int wb_radar_get_sampling_period(WbDeviceTag tag) {
  (void)tag;
  refused("wb_radar_get_sampling_period");
  return 0;
}

int wb_radar_get_number_of_targets(WbDeviceTag tag) {
  (void)tag;
  refused("wb_radar_get_number_of_targets");
  return 0;
}

const WbRadarTarget *wb_radar_get_targets(WbDeviceTag tag) {
  (void)tag;
  refused("wb_radar_get_targets");
  return NULL;
}

/* A radar's number: NaN, for no radar. */
static double radar_number(WbDeviceTag tag, const char *function) {
  (void)tag;
  refused(function);
  return NAN;
}

double wb_radar_get_min_range(WbDeviceTag tag) {
  return radar_number(tag, "wb_radar_get_min_range");
}

double wb_radar_get_max_range(WbDeviceTag tag) {
  return radar_number(tag, "wb_radar_get_max_range");
}

double wb_radar_get_horizontal_fov(WbDeviceTag tag) {
  return radar_number(tag, "wb_radar_get_horizontal_fov");
}

double wb_radar_get_vertical_fov(WbDeviceTag tag) {
  return radar_number(tag, "wb_radar_get_vertical_fov");
}

void wb_skin_set_bone_orientation(WbDeviceTag tag, int index, const double orientation[4],
                                  bool absolute) {
  (void)tag, (void)index, (void)orientation, (void)absolute;
  refused("wb_skin_set_bone_orientation");
}

void wb_skin_set_bone_position(WbDeviceTag tag, int index, const double position[3], bool absolute) {
  (void)tag, (void)index, (void)position, (void)absolute;
  refused("wb_skin_set_bone_position");
}

int wb_skin_get_bone_count(WbDeviceTag tag) {
  (void)tag;
  refused("wb_skin_get_bone_count");
  return 0;
}

const char *wb_skin_get_bone_name(WbDeviceTag tag, int index) {
  (void)tag, (void)index;
  refused("wb_skin_get_bone_name");
  return NULL;
}

const double *wb_skin_get_bone_orientation(WbDeviceTag tag, int index, bool absolute) {
  (void)tag, (void)index, (void)absolute;
  refused("wb_skin_get_bone_orientation");
  return NULL;
}

const double *wb_skin_get_bone_position(WbDeviceTag tag, int index, bool absolute) {
  (void)tag, (void)index, (void)absolute;
  refused("wb_skin_get_bone_position");
  return NULL;
}

void wb_vacuum_gripper_enable_presence(WbDeviceTag tag, int sampling_period) {
  (void)tag, (void)sampling_period;
  refused("wb_vacuum_gripper_enable_presence");
}

void wb_vacuum_gripper_disable_presence(WbDeviceTag tag) {
  (void)tag;
  refused("wb_vacuum_gripper_disable_presence");
}

int wb_vacuum_gripper_get_presence_sampling_period(WbDeviceTag tag) {
  (void)tag;
  refused("wb_vacuum_gripper_get_presence_sampling_period");
  return 0;
}

bool wb_vacuum_gripper_get_presence(WbDeviceTag tag) {
  (void)tag;
  refused("wb_vacuum_gripper_get_presence");
  return false;
}

void wb_vacuum_gripper_turn_on(WbDeviceTag tag) {
  (void)tag;
  refused("wb_vacuum_gripper_turn_on");
}

void wb_vacuum_gripper_turn_off(WbDeviceTag tag) {
  (void)tag;
  refused("wb_vacuum_gripper_turn_off");
}

bool wb_vacuum_gripper_is_on(WbDeviceTag tag) {
  (void)tag;
  refused("wb_vacuum_gripper_is_on");
  return false;
}
