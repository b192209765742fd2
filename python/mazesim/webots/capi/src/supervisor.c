/* Webots' Supervisor, Node and Field functions (reference manual, Supervisor page), served by
   mazesim's Python Supervisor over the link: mazesim numbers each node and field it hands out
   (a handle, 1, 2...), and the library keeps one reference per handle, with room for the
   strings and vectors the functions return. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <webots/supervisor.h>

#include "call.h"
#include "link.h"

struct WbNodeStructPrivate {
  int handle;
  char *def, *type_name, *base_type_name;
  double position[3], orientation[9], pose[16], center_of_mass[3], velocity[6];
};

struct WbFieldStructPrivate {
  int handle;
  WbFieldType type;
  char *name, *type_name, *text;
  double values[4];
};

static WbNodeRef *nodes;
static WbFieldRef *fields;
static int node_capacity, field_capacity;

static void *grow(void *array, int *capacity, int needed, size_t item) {
  if (needed < *capacity)
    return array;
  int wanted = *capacity ? 2 * *capacity : 64;
  while (wanted <= needed)
    wanted *= 2;
  void *grown = realloc(array, item * (size_t)wanted);
  if (!grown)
    link_failed("out of memory");
  memset((char *)grown + item * (size_t)*capacity, 0, item * (size_t)(wanted - *capacity));
  *capacity = wanted;
  return grown;
}

static void *made(size_t size) {
  void *memory = calloc(1, size);
  if (!memory)
    link_failed("out of memory");
  return memory;
}

/* The node of the answer's value `index` (a handle), or NULL. */
static WbNodeRef answer_node(int index) {
  int handle = answer_int(index);
  if (handle <= 0)
    return NULL;
  nodes = grow(nodes, &node_capacity, handle, sizeof(WbNodeRef));
  if (!nodes[handle]) {
    nodes[handle] = made(sizeof(struct WbNodeStructPrivate));
    nodes[handle]->handle = handle;
  }
  return nodes[handle];
}

/* The field of the answer (a handle, its type), named `name`, or NULL. */
static WbFieldRef answer_field(const char *name) {
  int handle = answer_int(0);
  if (handle <= 0)
    return NULL;
  fields = grow(fields, &field_capacity, handle, sizeof(WbFieldRef));
  if (!fields[handle]) {
    WbFieldRef field = made(sizeof(struct WbFieldStructPrivate));
    field->handle = handle;
    field->type = (WbFieldType)answer_int(1);
    field->name = made(strlen(name) + 1);
    strcpy(field->name, name);
    fields[handle] = field;
  }
  return fields[handle];
}

/* A call with no value but the function's name. */
static void call_plain(const char *function) {
  call_begin(function);
  call_end();
}

/* A call on a node (its handle first, 0 for NULL). */
static void call_node(const char *function, WbNodeRef node) {
  call_begin(function);
  call_int(node ? node->handle : 0);
}

static void call_field(const char *function, WbFieldRef field) {
  call_begin(function);
  call_int(field ? field->handle : 0);
}

/* Copies up to `count` numbers of the answer into `into` (NULL when the answer has none). */
static const double *numbers(double *into, int count) {
  int found;
  const double *values = answer_doubles(0, &found);
  if (!values)
    return NULL;
  for (int i = 0; i < count; i++)
    into[i] = i < found ? values[i] : 0.0;
  return into;
}

/* --- the simulation ------------------------------------------------------------------------ */

void wb_supervisor_simulation_quit(int status) {
  call_begin("wb_supervisor_simulation_quit");
  call_int(status);
  call_end();
}

void wb_supervisor_simulation_reset(void) {
  call_plain("wb_supervisor_simulation_reset");
}

void wb_supervisor_simulation_reset_physics(void) {
  call_plain("wb_supervisor_simulation_reset_physics");
}

void wb_supervisor_simulation_revert(void) {
  call_plain("wb_supervisor_world_reload");
}

void wb_supervisor_simulation_physics_reset(void) {
  call_plain("wb_supervisor_simulation_reset_physics");
}

WbSimulationMode wb_supervisor_simulation_get_mode(void) {
  call_plain("wb_supervisor_simulation_get_mode");
  return (WbSimulationMode)answer_int(0);
}

void wb_supervisor_simulation_set_mode(WbSimulationMode mode) {
  call_begin("wb_supervisor_simulation_set_mode");
  call_int(mode);
  call_end();
}

void wb_supervisor_world_load(const char *filename) {
  call_begin("wb_supervisor_world_load");
  call_text(filename);
  call_end();
}

bool wb_supervisor_world_save(const char *filename) {
  call_begin("wb_supervisor_world_save");
  call_text(filename);
  call_end();
  return answer_int(0) != 0;
}

void wb_supervisor_world_reload(void) {
  call_plain("wb_supervisor_world_reload");
}

void wb_supervisor_set_label(int id, const char *label, double x, double y, double size,
                             int color, double transparency, const char *font) {
  call_begin("wb_supervisor_set_label");
  call_int(id);
  call_text(label);
  call_double(x);
  call_double(y);
  call_double(size);
  call_int(color);
  call_double(transparency);
  call_text(font);
  call_end();
}

void wb_supervisor_export_image(const char *filename, int quality) {
  call_begin("wb_supervisor_export_image");
  call_text(filename);
  call_int(quality);
  call_end();
}

void wb_supervisor_movie_start_recording(const char *filename, int width, int height, int codec,
                                         int quality, int acceleration, bool caption) {
  call_begin("wb_supervisor_movie_start_recording");
  call_text(filename);
  call_int(width);
  call_int(height);
  call_int(codec);
  call_int(quality);
  call_int(acceleration);
  call_int(caption ? 1 : 0);
  call_end();
}

void wb_supervisor_movie_stop_recording(void) {
  call_plain("wb_supervisor_movie_stop_recording");
}

bool wb_supervisor_movie_is_ready(void) {
  call_plain("wb_supervisor_movie_is_ready");
  return answer_int(0) != 0;
}

bool wb_supervisor_movie_failed(void) {
  call_plain("wb_supervisor_movie_failed");
  return answer_int(0) != 0;
}

/* --- nodes --------------------------------------------------------------------------------- */

WbNodeRef wb_supervisor_node_get_root(void) {
  call_plain("wb_supervisor_node_get_root");
  return answer_node(0);
}

WbNodeRef wb_supervisor_node_get_self(void) {
  call_plain("wb_supervisor_node_get_self");
  return answer_node(0);
}

WbNodeRef wb_supervisor_node_get_from_def(const char *def) {
  call_begin("wb_supervisor_node_get_from_def");
  call_text(def);
  call_end();
  return answer_node(0);
}

WbNodeRef wb_supervisor_node_get_from_id(int id) {
  call_begin("wb_supervisor_node_get_from_id");
  call_int(id);
  call_end();
  return answer_node(0);
}

WbNodeRef wb_supervisor_node_get_from_device(WbDeviceTag tag) {
  call_begin("wb_supervisor_node_get_from_device");
  call_int(tag);
  call_end();
  return answer_node(0);
}

WbNodeRef wb_supervisor_node_get_selected(void) {
  call_plain("wb_supervisor_node_get_selected");
  return answer_node(0);
}

WbNodeRef wb_supervisor_node_get_parent_node(WbNodeRef node) {
  call_node("wb_supervisor_node_get_parent_node", node);
  call_end();
  return answer_node(0);
}

int wb_supervisor_node_get_id(WbNodeRef node) {
  call_node("wb_supervisor_node_get_id", node);
  call_end();
  return answer_type(0) == VALUE_NONE ? -1 : answer_int(0);
}

/* A node's text, asked once and kept in `slot` ("" for no node). */
static const char *node_text(WbNodeRef node, char **slot, const char *function) {
  if (slot && *slot)
    return *slot;
  call_node(function, node);
  call_end();
  char *text = answer_text(0);
  if (!slot) {
    free(text);
    return "";
  }
  *slot = text ? text : made(1);
  return *slot;
}

const char *wb_supervisor_node_get_def(WbNodeRef node) {
  return node_text(node, node ? &node->def : NULL, "wb_supervisor_node_get_def");
}

const char *wb_supervisor_node_get_type_name(WbNodeRef node) {
  return node_text(node, node ? &node->type_name : NULL, "wb_supervisor_node_get_type_name");
}

const char *wb_supervisor_node_get_base_type_name(WbNodeRef node) {
  return node_text(node, node ? &node->base_type_name : NULL,
                   "wb_supervisor_node_get_base_type_name");
}

WbNodeType wb_supervisor_node_get_type(WbNodeRef node) {
  call_node("wb_supervisor_node_get_type", node);
  call_end();
  return (WbNodeType)answer_int(0);
}

bool wb_supervisor_node_is_proto(WbNodeRef node) {
  call_node("wb_supervisor_node_is_proto", node);
  call_end();
  return answer_int(0) != 0;
}

static WbFieldRef field_of(WbNodeRef node, const char *name, const char *function) {
  /* A NULL node is refused first, by the call. */
  if (node && (!name || !name[0])) {
    link_error(function, "() called with a NULL or empty 'field_name' argument.");
    return NULL;
  }
  call_node(function, node);
  call_text(name);
  call_end();
  return name ? answer_field(name) : NULL;
}

WbFieldRef wb_supervisor_node_get_field(WbNodeRef node, const char *field_name) {
  return field_of(node, field_name, "wb_supervisor_node_get_field");
}

WbFieldRef wb_supervisor_node_get_proto_field(WbNodeRef node, const char *field_name) {
  return field_of(node, field_name, "wb_supervisor_node_get_proto_field");
}

WbFieldRef wb_supervisor_node_get_field_by_index(WbNodeRef node, int index) {
  /* The name of the field at `index` (Webots' error when there is none), then that field. */
  call_node("wb_supervisor_node_get_field_by_index", node);
  call_int(index);
  call_end();
  char *name = answer_text(0);
  if (!name)
    return NULL;
  WbFieldRef field = field_of(node, name, "wb_supervisor_node_get_field");
  free(name);
  return field;
}

int wb_supervisor_node_get_number_of_fields(WbNodeRef node) {
  call_node("wb_supervisor_node_get_number_of_fields", node);
  call_end();
  return answer_type(0) == VALUE_NONE ? -1 : answer_int(0);
}

/* What Webots' node getters give for a NULL node or a node without the vector (a position of a
   node that is no Transform): 16 NaNs, never NULL, so a controller that reads it goes on. */
static const double no_vector[16] = {NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN,
                                     NAN, NAN, NAN, NAN, NAN, NAN, NAN, NAN};

/* A vector of a node, asked each time (a node moves) and kept in `into`. */
static const double *node_vector(WbNodeRef node, double *into, int count, const char *function) {
  call_node(function, node);
  call_end();
  const double *values = node ? numbers(into, count) : NULL;
  return values ? values : no_vector;
}

const double *wb_supervisor_node_get_position(WbNodeRef node) {
  return node_vector(node, node ? node->position : NULL, 3, "wb_supervisor_node_get_position");
}

const double *wb_supervisor_node_get_orientation(WbNodeRef node) {
  return node_vector(node, node ? node->orientation : NULL, 9,
                     "wb_supervisor_node_get_orientation");
}

const double *wb_supervisor_node_get_center_of_mass(WbNodeRef node) {
  return node_vector(node, node ? node->center_of_mass : NULL, 3,
                     "wb_supervisor_node_get_center_of_mass");
}

const double *wb_supervisor_node_get_velocity(WbNodeRef node) {
  return node_vector(node, node ? node->velocity : NULL, 6, "wb_supervisor_node_get_velocity");
}

const double *wb_supervisor_node_get_pose(WbNodeRef node, WbNodeRef from_node) {
  call_node("wb_supervisor_node_get_pose", node);
  call_int(from_node ? from_node->handle : 0);
  call_end();
  const double *values = node ? numbers(node->pose, 16) : NULL;
  return values ? values : no_vector;
}

void wb_supervisor_node_set_velocity(WbNodeRef node, const double velocity[6]) {
  call_node("wb_supervisor_node_set_velocity", node);
  call_doubles(velocity, velocity ? 6 : -1);
  call_end();
}

void wb_supervisor_node_reset_physics(WbNodeRef node) {
  call_node("wb_supervisor_node_reset_physics", node);
  call_end();
}

void wb_supervisor_node_restart_controller(WbNodeRef node) {
  call_node("wb_supervisor_node_restart_controller", node);
  call_end();
}

bool wb_supervisor_node_get_static_balance(WbNodeRef node) {
  call_node("wb_supervisor_node_get_static_balance", node);
  call_end();
  return answer_int(0) != 0;
}

void wb_supervisor_node_remove(WbNodeRef node) {
  call_node("wb_supervisor_node_remove", node);
  call_end();
}

/* Numbers per contact point on the link: x, y, z, node id. */
#define CONTACT_NUMBERS 4

WbContactPoint *wb_supervisor_node_get_contact_points(WbNodeRef node, bool include_descendants,
                                                      int *size) {
  static WbContactPoint *points;
  if (size)
    *size = 0;
  call_node("wb_supervisor_node_get_contact_points", node);
  call_int(include_descendants);
  call_end();
  int count;
  const double *numbers = answer_doubles(0, &count);
  int point_count = numbers ? count / CONTACT_NUMBERS : 0;
  if (point_count == 0)
    return NULL;
  WbContactPoint *grown = realloc(points, sizeof(WbContactPoint) * (size_t)point_count);
  if (!grown)
    link_failed("out of memory");
  points = grown;
  for (int i = 0; i < point_count; i++) {
    const double *number = numbers + CONTACT_NUMBERS * i;
    points[i].point[0] = number[0];
    points[i].point[1] = number[1];
    points[i].point[2] = number[2];
    points[i].node_id = (int)number[3];
  }
  if (size)
    *size = point_count;
  return points;
}

/* --- fields -------------------------------------------------------------------------------- */

WbFieldType wb_supervisor_field_get_type(WbFieldRef field) {
  return field ? field->type : WB_NO_FIELD;
}

const char *wb_supervisor_field_get_name(WbFieldRef field) {
  return field ? field->name : "";
}

const char *wb_supervisor_field_get_type_name(WbFieldRef field) {
  if (!field)
    return "";
  if (!field->type_name) {
    call_field("wb_supervisor_field_get_type_name", field);
    call_end();
    field->type_name = answer_text(0);
    if (!field->type_name)
      field->type_name = made(1);
  }
  return field->type_name;
}

int wb_supervisor_field_get_count(WbFieldRef field) {
  call_field("wb_supervisor_field_get_count", field);
  call_end();
  return answer_type(0) == VALUE_NONE ? -1 : answer_int(0);
}

/* A field's single value, asked each time. */
static void ask(WbFieldRef field, const char *function) {
  call_field(function, field);
  call_end();
}

bool wb_supervisor_field_get_sf_bool(WbFieldRef field) {
  ask(field, "wb_supervisor_field_get_sf_bool");
  return answer_int(0) != 0;
}

int wb_supervisor_field_get_sf_int32(WbFieldRef field) {
  ask(field, "wb_supervisor_field_get_sf_int32");
  return answer_int(0);
}

double wb_supervisor_field_get_sf_float(WbFieldRef field) {
  ask(field, "wb_supervisor_field_get_sf_float");
  return answer_type(0) == VALUE_NONE ? 0.0 : answer_double(0);
}

static const double *field_vector(WbFieldRef field, int count, const char *function) {
  ask(field, function);
  return field ? numbers(field->values, count) : NULL;
}

const double *wb_supervisor_field_get_sf_vec2f(WbFieldRef field) {
  return field_vector(field, 2, "wb_supervisor_field_get_sf_vec2f");
}

const double *wb_supervisor_field_get_sf_vec3f(WbFieldRef field) {
  return field_vector(field, 3, "wb_supervisor_field_get_sf_vec3f");
}

const double *wb_supervisor_field_get_sf_rotation(WbFieldRef field) {
  return field_vector(field, 4, "wb_supervisor_field_get_sf_rotation");
}

const double *wb_supervisor_field_get_sf_color(WbFieldRef field) {
  return field_vector(field, 3, "wb_supervisor_field_get_sf_color");
}

const char *wb_supervisor_field_get_sf_string(WbFieldRef field) {
  ask(field, "wb_supervisor_field_get_sf_string");
  if (!field)
    return "";
  free(field->text);
  field->text = answer_text(0);
  return field->text ? field->text : "";
}

WbNodeRef wb_supervisor_field_get_sf_node(WbFieldRef field) {
  ask(field, "wb_supervisor_field_get_sf_node");
  return answer_node(0);
}

WbNodeRef wb_supervisor_field_get_mf_node(WbFieldRef field, int index) {
  call_field("wb_supervisor_field_get_mf_node", field);
  call_int(index);
  call_end();
  return answer_node(0);
}

/* An item of a list field of values, asked each time. */
static void ask_item(WbFieldRef field, const char *function, int index) {
  call_field(function, field);
  call_int(index);
  call_end();
}

bool wb_supervisor_field_get_mf_bool(WbFieldRef field, int index) {
  ask_item(field, "wb_supervisor_field_get_mf_bool", index);
  return answer_int(0) != 0;
}

int wb_supervisor_field_get_mf_int32(WbFieldRef field, int index) {
  ask_item(field, "wb_supervisor_field_get_mf_int32", index);
  return answer_int(0);
}

double wb_supervisor_field_get_mf_float(WbFieldRef field, int index) {
  ask_item(field, "wb_supervisor_field_get_mf_float", index);
  return answer_type(0) == VALUE_NONE ? 0.0 : answer_double(0);
}

static const double *item_vector(WbFieldRef field, int index, int count, const char *function) {
  ask_item(field, function, index);
  return field ? numbers(field->values, count) : NULL;
}

const double *wb_supervisor_field_get_mf_vec2f(WbFieldRef field, int index) {
  return item_vector(field, index, 2, "wb_supervisor_field_get_mf_vec2f");
}

const double *wb_supervisor_field_get_mf_vec3f(WbFieldRef field, int index) {
  return item_vector(field, index, 3, "wb_supervisor_field_get_mf_vec3f");
}

const double *wb_supervisor_field_get_mf_rotation(WbFieldRef field, int index) {
  return item_vector(field, index, 4, "wb_supervisor_field_get_mf_rotation");
}

const double *wb_supervisor_field_get_mf_color(WbFieldRef field, int index) {
  return item_vector(field, index, 3, "wb_supervisor_field_get_mf_color");
}

const char *wb_supervisor_field_get_mf_string(WbFieldRef field, int index) {
  ask_item(field, "wb_supervisor_field_get_mf_string", index);
  if (!field)
    return "";
  free(field->text);
  field->text = answer_text(0);
  return field->text ? field->text : "";
}

void wb_supervisor_field_set_sf_bool(WbFieldRef field, bool value) {
  call_field("wb_supervisor_field_set_sf_bool", field);
  call_int(value ? 1 : 0);
  call_end();
}

void wb_supervisor_field_set_sf_int32(WbFieldRef field, int value) {
  call_field("wb_supervisor_field_set_sf_int32", field);
  call_int(value);
  call_end();
}

void wb_supervisor_field_set_sf_float(WbFieldRef field, double value) {
  call_field("wb_supervisor_field_set_sf_float", field);
  call_double(value);
  call_end();
}

static void set_vector(WbFieldRef field, const double *values, int count, const char *function) {
  call_field(function, field);
  call_doubles(values, values ? count : -1);
  call_end();
}

/* An item of a list field of values set or inserted: a whole number or flag, a number
   (count -2: one double, sent as a number), or a vector of count numbers. */
static void item_int(WbFieldRef field, int index, int value, const char *function) {
  call_field(function, field);
  call_int(index);
  call_int(value);
  call_end();
}

static void item_text(WbFieldRef field, int index, const char *value, const char *function) {
  call_field(function, field);
  call_int(index);
  call_text(value);
  call_end();
}

static void set_item(WbFieldRef field, int index, const double *values, int count,
                     const char *function) {
  call_field(function, field);
  call_int(index);
  if (count == -2)
    call_double(*values);
  else
    call_doubles(values, values ? count : -1);
  call_end();
}

/* Webots' setter and inserter of one kind of list item (wb_supervisor_field_set_mf_KIND and
   wb_supervisor_field_insert_mf_KIND): the same call under the two names, `function` naming
   the one called. */
#define LIST_ITEM_WRITERS(kind, parameter, ...)                                                 \
  void wb_supervisor_field_set_mf_##kind(WbFieldRef field, int index, parameter) {              \
    const char *function = "wb_supervisor_field_set_mf_" #kind;                                 \
    __VA_ARGS__;                                                                                \
  }                                                                                             \
  void wb_supervisor_field_insert_mf_##kind(WbFieldRef field, int index, parameter) {           \
    const char *function = "wb_supervisor_field_insert_mf_" #kind;                              \
    __VA_ARGS__;                                                                                \
  }

LIST_ITEM_WRITERS(bool, bool value, item_int(field, index, value ? 1 : 0, function))
LIST_ITEM_WRITERS(int32, int value, item_int(field, index, value, function))
LIST_ITEM_WRITERS(float, double value, set_item(field, index, &value, -2, function))
LIST_ITEM_WRITERS(vec2f, const double values[2], set_item(field, index, values, 2, function))
LIST_ITEM_WRITERS(vec3f, const double values[3], set_item(field, index, values, 3, function))
LIST_ITEM_WRITERS(rotation, const double values[4], set_item(field, index, values, 4, function))
LIST_ITEM_WRITERS(color, const double values[3], set_item(field, index, values, 3, function))
LIST_ITEM_WRITERS(string, const char *value, item_text(field, index, value, function))

void wb_supervisor_field_set_sf_vec2f(WbFieldRef field, const double values[2]) {
  set_vector(field, values, 2, "wb_supervisor_field_set_sf_vec2f");
}

void wb_supervisor_field_set_sf_vec3f(WbFieldRef field, const double values[3]) {
  set_vector(field, values, 3, "wb_supervisor_field_set_sf_vec3f");
}

void wb_supervisor_field_set_sf_rotation(WbFieldRef field, const double values[4]) {
  set_vector(field, values, 4, "wb_supervisor_field_set_sf_rotation");
}

void wb_supervisor_field_set_sf_color(WbFieldRef field, const double values[3]) {
  set_vector(field, values, 3, "wb_supervisor_field_set_sf_color");
}

void wb_supervisor_field_set_sf_string(WbFieldRef field, const char *value) {
  /* A NULL field is refused first, by the call. */
  if (field && !value) {
    link_error("wb_supervisor_field_set_sf_string", "() called with a NULL string argument.");
    return;
  }
  call_field("wb_supervisor_field_set_sf_string", field);
  call_text(value);
  call_end();
}

void wb_supervisor_field_import_mf_node_from_string(WbFieldRef field, int position,
                                                    const char *node_string) {
  call_field("wb_supervisor_field_import_mf_node_from_string", field);
  call_int(position);
  call_text(node_string);
  call_end();
}

void wb_supervisor_field_remove_mf(WbFieldRef field, int index) {
  call_field("wb_supervisor_field_remove_mf", field);
  call_int(index);
  call_end();
}

void wb_supervisor_field_import_sf_node_from_string(WbFieldRef field, const char *node_string) {
  call_field("wb_supervisor_field_import_sf_node_from_string", field);
  call_text(node_string);
  call_end();
}

void wb_supervisor_field_import_mf_node(WbFieldRef field, int position, const char *filename) {
  call_field("wb_supervisor_field_import_mf_node", field);
  call_int(position);
  call_text(filename);
  call_end();
}

void wb_supervisor_field_import_sf_node(WbFieldRef field, const char *filename) {
  call_field("wb_supervisor_field_import_sf_node", field);
  call_text(filename);
  call_end();
}

void wb_supervisor_field_remove_sf(WbFieldRef field) {
  call_field("wb_supervisor_field_remove_sf", field);
  call_end();
}

bool wb_supervisor_virtual_reality_headset_is_used(void) {
  call_plain("wb_supervisor_virtual_reality_headset_is_used");
  return answer_int(0) != 0;
}
