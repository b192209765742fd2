/* Webots' supervisor functions (<webots/supervisor.h>), as the reference manual's Supervisor,
   Node and Field pages describe them (https://cyberbotics.com/doc/reference/supervisor). They
   are served by mazesim's Python Supervisor (mazesim/webots/supervisor.py), so a C supervisor
   sees and moves the world's nodes as a Python one does. Node and field references stay valid
   for the whole run; a vector a function returns stays valid until the same function is
   called again on the same node or field. As for a Python controller, the first supervisor
   function a controller calls makes its robot a supervisor. */
#ifndef WB_SUPERVISOR_H
#define WB_SUPERVISOR_H

#include <webots/nodes.h>
#include <webots/robot.h>
#include <webots/types.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct WbNodeStructPrivate *WbNodeRef;
typedef struct WbFieldStructPrivate *WbFieldRef;

/* A point where a node touches another, and the id of the node it belongs to. */
typedef struct {
  double point[3];
  int node_id;
} WbContactPoint;

typedef enum {
  WB_NO_FIELD = 0x00,
  WB_SF_BOOL = 0x01,
  WB_SF_INT32 = 0x02,
  WB_SF_FLOAT = 0x03,
  WB_SF_VEC2F = 0x04,
  WB_SF_VEC3F = 0x05,
  WB_SF_ROTATION = 0x06,
  WB_SF_COLOR = 0x07,
  WB_SF_STRING = 0x08,
  WB_SF_NODE = 0x09,
  WB_MF = 0x10,
  WB_MF_BOOL = 0x11,
  WB_MF_INT32 = 0x12,
  WB_MF_FLOAT = 0x13,
  WB_MF_VEC2F = 0x14,
  WB_MF_VEC3F = 0x15,
  WB_MF_ROTATION = 0x16,
  WB_MF_COLOR = 0x17,
  WB_MF_STRING = 0x18,
  WB_MF_NODE = 0x19
} WbFieldType;

typedef enum {
  WB_SUPERVISOR_SIMULATION_MODE_PAUSE = 0,
  WB_SUPERVISOR_SIMULATION_MODE_REAL_TIME,
  WB_SUPERVISOR_SIMULATION_MODE_FAST
} WbSimulationMode;

/* The simulation. */
void wb_supervisor_simulation_quit(int status);
void wb_supervisor_simulation_reset(void);
void wb_supervisor_simulation_reset_physics(void);
WbSimulationMode wb_supervisor_simulation_get_mode(void);
void wb_supervisor_simulation_set_mode(WbSimulationMode mode);
void wb_supervisor_world_load(const char *filename);
bool wb_supervisor_world_save(const char *filename);
void wb_supervisor_world_reload(void);
void wb_supervisor_set_label(int id, const char *label, double x, double y, double size,
                             int color, double transparency, const char *font);
void wb_supervisor_export_image(const char *filename, int quality);
void wb_supervisor_movie_start_recording(const char *filename, int width, int height, int codec,
                                         int quality, int acceleration, bool caption);
void wb_supervisor_movie_stop_recording(void);
bool wb_supervisor_movie_is_ready(void);
bool wb_supervisor_movie_failed(void);
/* The names of Webots 8 and before. */
void wb_supervisor_simulation_revert(void);
void wb_supervisor_simulation_physics_reset(void);

/* Nodes. */
WbNodeRef wb_supervisor_node_get_root(void);
WbNodeRef wb_supervisor_node_get_self(void);
WbNodeRef wb_supervisor_node_get_from_def(const char *def);
WbNodeRef wb_supervisor_node_get_from_id(int id);
WbNodeRef wb_supervisor_node_get_from_device(WbDeviceTag tag);
WbNodeRef wb_supervisor_node_get_selected(void);
WbNodeRef wb_supervisor_node_get_parent_node(WbNodeRef node);
int wb_supervisor_node_get_id(WbNodeRef node);
const char *wb_supervisor_node_get_def(WbNodeRef node);
WbNodeType wb_supervisor_node_get_type(WbNodeRef node);
const char *wb_supervisor_node_get_type_name(WbNodeRef node);
const char *wb_supervisor_node_get_base_type_name(WbNodeRef node);
bool wb_supervisor_node_is_proto(WbNodeRef node);
WbFieldRef wb_supervisor_node_get_field(WbNodeRef node, const char *field_name);
WbFieldRef wb_supervisor_node_get_field_by_index(WbNodeRef node, int index);
WbFieldRef wb_supervisor_node_get_proto_field(WbNodeRef node, const char *field_name);
int wb_supervisor_node_get_number_of_fields(WbNodeRef node);
const double *wb_supervisor_node_get_position(WbNodeRef node);
const double *wb_supervisor_node_get_orientation(WbNodeRef node);
const double *wb_supervisor_node_get_pose(WbNodeRef node, WbNodeRef from_node);
const double *wb_supervisor_node_get_center_of_mass(WbNodeRef node);
const double *wb_supervisor_node_get_velocity(WbNodeRef node);
void wb_supervisor_node_set_velocity(WbNodeRef node, const double velocity[6]);
void wb_supervisor_node_reset_physics(WbNodeRef node);
void wb_supervisor_node_restart_controller(WbNodeRef node);
bool wb_supervisor_node_get_static_balance(WbNodeRef node);
void wb_supervisor_node_remove(WbNodeRef node);
/* The node's contact points (its descendants' too when asked), `*size` of them, valid until
   the next call on the same node. */
WbContactPoint *wb_supervisor_node_get_contact_points(WbNodeRef node, bool include_descendants,
                                                      int *size);

/* Fields. */
WbFieldType wb_supervisor_field_get_type(WbFieldRef field);
const char *wb_supervisor_field_get_type_name(WbFieldRef field);
const char *wb_supervisor_field_get_name(WbFieldRef field);
int wb_supervisor_field_get_count(WbFieldRef field);
bool wb_supervisor_field_get_sf_bool(WbFieldRef field);
int wb_supervisor_field_get_sf_int32(WbFieldRef field);
double wb_supervisor_field_get_sf_float(WbFieldRef field);
const double *wb_supervisor_field_get_sf_vec2f(WbFieldRef field);
const double *wb_supervisor_field_get_sf_vec3f(WbFieldRef field);
const double *wb_supervisor_field_get_sf_rotation(WbFieldRef field);
const double *wb_supervisor_field_get_sf_color(WbFieldRef field);
const char *wb_supervisor_field_get_sf_string(WbFieldRef field);
WbNodeRef wb_supervisor_field_get_sf_node(WbFieldRef field);
WbNodeRef wb_supervisor_field_get_mf_node(WbFieldRef field, int index);
bool wb_supervisor_field_get_mf_bool(WbFieldRef field, int index);
int wb_supervisor_field_get_mf_int32(WbFieldRef field, int index);
double wb_supervisor_field_get_mf_float(WbFieldRef field, int index);
const double *wb_supervisor_field_get_mf_vec2f(WbFieldRef field, int index);
const double *wb_supervisor_field_get_mf_vec3f(WbFieldRef field, int index);
const double *wb_supervisor_field_get_mf_rotation(WbFieldRef field, int index);
const double *wb_supervisor_field_get_mf_color(WbFieldRef field, int index);
const char *wb_supervisor_field_get_mf_string(WbFieldRef field, int index);
void wb_supervisor_field_set_mf_bool(WbFieldRef field, int index, bool value);
void wb_supervisor_field_set_mf_int32(WbFieldRef field, int index, int value);
void wb_supervisor_field_set_mf_float(WbFieldRef field, int index, double value);
void wb_supervisor_field_set_mf_vec2f(WbFieldRef field, int index, const double values[2]);
void wb_supervisor_field_set_mf_vec3f(WbFieldRef field, int index, const double values[3]);
void wb_supervisor_field_set_mf_rotation(WbFieldRef field, int index, const double values[4]);
void wb_supervisor_field_set_mf_color(WbFieldRef field, int index, const double values[3]);
void wb_supervisor_field_set_mf_string(WbFieldRef field, int index, const char *value);
void wb_supervisor_field_insert_mf_bool(WbFieldRef field, int index, bool value);
void wb_supervisor_field_insert_mf_int32(WbFieldRef field, int index, int value);
void wb_supervisor_field_insert_mf_float(WbFieldRef field, int index, double value);
void wb_supervisor_field_insert_mf_vec2f(WbFieldRef field, int index, const double values[2]);
void wb_supervisor_field_insert_mf_vec3f(WbFieldRef field, int index, const double values[3]);
void wb_supervisor_field_insert_mf_rotation(WbFieldRef field, int index, const double values[4]);
void wb_supervisor_field_insert_mf_color(WbFieldRef field, int index, const double values[3]);
void wb_supervisor_field_insert_mf_string(WbFieldRef field, int index, const char *value);
void wb_supervisor_field_set_sf_bool(WbFieldRef field, bool value);
void wb_supervisor_field_set_sf_int32(WbFieldRef field, int value);
void wb_supervisor_field_set_sf_float(WbFieldRef field, double value);
void wb_supervisor_field_set_sf_vec2f(WbFieldRef field, const double values[2]);
void wb_supervisor_field_set_sf_vec3f(WbFieldRef field, const double values[3]);
void wb_supervisor_field_set_sf_rotation(WbFieldRef field, const double values[4]);
void wb_supervisor_field_set_sf_color(WbFieldRef field, const double values[3]);
void wb_supervisor_field_set_sf_string(WbFieldRef field, const char *value);
void wb_supervisor_field_import_mf_node_from_string(WbFieldRef field, int position,
                                                    const char *node_string);
void wb_supervisor_field_remove_mf(WbFieldRef field, int index);
void wb_supervisor_field_import_sf_node_from_string(WbFieldRef field, const char *node_string);
void wb_supervisor_field_import_mf_node(WbFieldRef field, int position, const char *filename);
void wb_supervisor_field_import_sf_node(WbFieldRef field, const char *filename);
void wb_supervisor_field_remove_sf(WbFieldRef field);
/* False: a headless run has no headset. */
bool wb_supervisor_virtual_reality_headset_is_used(void);

#ifdef __cplusplus
}
#endif

#endif
