// Webots' C++ Node and Field classes (<webots/Node.hpp>, <webots/Field.hpp>), as the reference
// manual's Supervisor page describes them (https://cyberbotics.com/doc/reference/supervisor),
// over mazesim's C supervisor functions. As in Webots, the library owns the objects: one per
// node or field, made when first handed out.
#ifndef WB_NODE_HPP
#define WB_NODE_HPP

#include <map>
#include <string>

#include <webots/supervisor.h>

namespace webots {
  class Node;

  class Field {
  public:
    enum FieldType {
      NO_FIELD = WB_NO_FIELD,
      SF_BOOL = WB_SF_BOOL,
      SF_INT32 = WB_SF_INT32,
      SF_FLOAT = WB_SF_FLOAT,
      SF_VEC2F = WB_SF_VEC2F,
      SF_VEC3F = WB_SF_VEC3F,
      SF_ROTATION = WB_SF_ROTATION,
      SF_COLOR = WB_SF_COLOR,
      SF_STRING = WB_SF_STRING,
      SF_NODE = WB_SF_NODE,
      MF = WB_MF,
      MF_BOOL = WB_MF_BOOL,
      MF_INT32 = WB_MF_INT32,
      MF_FLOAT = WB_MF_FLOAT,
      MF_VEC2F = WB_MF_VEC2F,
      MF_VEC3F = WB_MF_VEC3F,
      MF_ROTATION = WB_MF_ROTATION,
      MF_COLOR = WB_MF_COLOR,
      MF_STRING = WB_MF_STRING,
      MF_NODE = WB_MF_NODE
    };
    // The Field of a C reference (NULL for NULL).
    static Field *findField(WbFieldRef ref) {
      if (!ref)
        return 0;
      std::map<WbFieldRef, Field *> &known = fields();
      std::map<WbFieldRef, Field *>::iterator found = known.find(ref);
      if (found != known.end())
        return found->second;
      Field *made = new Field(ref);
      known[ref] = made;
      return made;
    }
    FieldType getType() const { return static_cast<FieldType>(wb_supervisor_field_get_type(ref)); }
    std::string getTypeName() const { return wb_supervisor_field_get_type_name(ref); }
    std::string getName() const { return wb_supervisor_field_get_name(ref); }
    int getCount() const { return wb_supervisor_field_get_count(ref); }
    bool getSFBool() const { return wb_supervisor_field_get_sf_bool(ref); }
    int getSFInt32() const { return wb_supervisor_field_get_sf_int32(ref); }
    double getSFFloat() const { return wb_supervisor_field_get_sf_float(ref); }
    const double *getSFVec2f() const { return wb_supervisor_field_get_sf_vec2f(ref); }
    const double *getSFVec3f() const { return wb_supervisor_field_get_sf_vec3f(ref); }
    const double *getSFRotation() const { return wb_supervisor_field_get_sf_rotation(ref); }
    const double *getSFColor() const { return wb_supervisor_field_get_sf_color(ref); }
    std::string getSFString() const { return wb_supervisor_field_get_sf_string(ref); }
    inline Node *getSFNode() const;
    inline Node *getMFNode(int index) const;
    bool getMFBool(int index) const { return wb_supervisor_field_get_mf_bool(ref, index); }
    int getMFInt32(int index) const { return wb_supervisor_field_get_mf_int32(ref, index); }
    double getMFFloat(int index) const { return wb_supervisor_field_get_mf_float(ref, index); }
    const double *getMFVec2f(int index) const {
      return wb_supervisor_field_get_mf_vec2f(ref, index);
    }
    const double *getMFVec3f(int index) const {
      return wb_supervisor_field_get_mf_vec3f(ref, index);
    }
    const double *getMFRotation(int index) const {
      return wb_supervisor_field_get_mf_rotation(ref, index);
    }
    const double *getMFColor(int index) const {
      return wb_supervisor_field_get_mf_color(ref, index);
    }
    std::string getMFString(int index) const { return wb_supervisor_field_get_mf_string(ref, index); }
    void setMFBool(int index, bool value) { wb_supervisor_field_set_mf_bool(ref, index, value); }
    void setMFInt32(int index, int value) { wb_supervisor_field_set_mf_int32(ref, index, value); }
    void setMFFloat(int index, double value) { wb_supervisor_field_set_mf_float(ref, index, value); }
    void setMFVec2f(int index, const double values[2]) {
      wb_supervisor_field_set_mf_vec2f(ref, index, values);
    }
    void setMFVec3f(int index, const double values[3]) {
      wb_supervisor_field_set_mf_vec3f(ref, index, values);
    }
    void setMFRotation(int index, const double values[4]) {
      wb_supervisor_field_set_mf_rotation(ref, index, values);
    }
    void setMFColor(int index, const double values[3]) {
      wb_supervisor_field_set_mf_color(ref, index, values);
    }
    void setMFString(int index, const std::string &value) {
      wb_supervisor_field_set_mf_string(ref, index, value.c_str());
    }
    void insertMFBool(int index, bool value) { wb_supervisor_field_insert_mf_bool(ref, index, value); }
    void insertMFInt32(int index, int value) { wb_supervisor_field_insert_mf_int32(ref, index, value); }
    void insertMFFloat(int index, double value) { wb_supervisor_field_insert_mf_float(ref, index, value); }
    void insertMFVec2f(int index, const double values[2]) {
      wb_supervisor_field_insert_mf_vec2f(ref, index, values);
    }
    void insertMFVec3f(int index, const double values[3]) {
      wb_supervisor_field_insert_mf_vec3f(ref, index, values);
    }
    void insertMFRotation(int index, const double values[4]) {
      wb_supervisor_field_insert_mf_rotation(ref, index, values);
    }
    void insertMFColor(int index, const double values[3]) {
      wb_supervisor_field_insert_mf_color(ref, index, values);
    }
    void insertMFString(int index, const std::string &value) {
      wb_supervisor_field_insert_mf_string(ref, index, value.c_str());
    }
    void setSFBool(bool value) { wb_supervisor_field_set_sf_bool(ref, value); }
    void setSFInt32(int value) { wb_supervisor_field_set_sf_int32(ref, value); }
    void setSFFloat(double value) { wb_supervisor_field_set_sf_float(ref, value); }
    void setSFVec2f(const double values[2]) { wb_supervisor_field_set_sf_vec2f(ref, values); }
    void setSFVec3f(const double values[3]) { wb_supervisor_field_set_sf_vec3f(ref, values); }
    void setSFRotation(const double values[4]) { wb_supervisor_field_set_sf_rotation(ref, values); }
    void setSFColor(const double values[3]) { wb_supervisor_field_set_sf_color(ref, values); }
    void setSFString(const std::string &value) {
      wb_supervisor_field_set_sf_string(ref, value.c_str());
    }
    void importMFNodeFromString(int position, const std::string &nodeString) {
      wb_supervisor_field_import_mf_node_from_string(ref, position, nodeString.c_str());
    }
    void removeMF(int index) { wb_supervisor_field_remove_mf(ref, index); }
    void importSFNodeFromString(const std::string &nodeString) {
      wb_supervisor_field_import_sf_node_from_string(ref, nodeString.c_str());
    }
    void importMFNode(int position, const std::string &filename) {
      wb_supervisor_field_import_mf_node(ref, position, filename.c_str());
    }
    void importSFNode(const std::string &filename) {
      wb_supervisor_field_import_sf_node(ref, filename.c_str());
    }
    void removeSF() { wb_supervisor_field_remove_sf(ref); }

  private:
    explicit Field(WbFieldRef ref) : ref(ref) {}
    static std::map<WbFieldRef, Field *> &fields() {
      static std::map<WbFieldRef, Field *> known;
      return known;
    }
    WbFieldRef ref;
  };

  // Webots' C++ contact point is its C struct.
  typedef WbContactPoint ContactPoint;

  class Node {
  public:
    enum Type {
      NO_NODE = WB_NODE_NO_NODE,
      APPEARANCE = WB_NODE_APPEARANCE,
      BACKGROUND = WB_NODE_BACKGROUND,
      BILLBOARD = WB_NODE_BILLBOARD,
      BOX = WB_NODE_BOX,
      CAD_SHAPE = WB_NODE_CAD_SHAPE,
      CAPSULE = WB_NODE_CAPSULE,
      COLOR = WB_NODE_COLOR,
      CONE = WB_NODE_CONE,
      COORDINATE = WB_NODE_COORDINATE,
      CYLINDER = WB_NODE_CYLINDER,
      DIRECTIONAL_LIGHT = WB_NODE_DIRECTIONAL_LIGHT,
      ELEVATION_GRID = WB_NODE_ELEVATION_GRID,
      FOG = WB_NODE_FOG,
      GROUP = WB_NODE_GROUP,
      IMAGE_TEXTURE = WB_NODE_IMAGE_TEXTURE,
      INDEXED_FACE_SET = WB_NODE_INDEXED_FACE_SET,
      INDEXED_LINE_SET = WB_NODE_INDEXED_LINE_SET,
      MATERIAL = WB_NODE_MATERIAL,
      MESH = WB_NODE_MESH,
      MUSCLE = WB_NODE_MUSCLE,
      NORMAL = WB_NODE_NORMAL,
      PBR_APPEARANCE = WB_NODE_PBR_APPEARANCE,
      PLANE = WB_NODE_PLANE,
      POINT_LIGHT = WB_NODE_POINT_LIGHT,
      POINT_SET = WB_NODE_POINT_SET,
      POSE = WB_NODE_POSE,
      SHAPE = WB_NODE_SHAPE,
      SPHERE = WB_NODE_SPHERE,
      SPOT_LIGHT = WB_NODE_SPOT_LIGHT,
      TEXTURE_COORDINATE = WB_NODE_TEXTURE_COORDINATE,
      TEXTURE_TRANSFORM = WB_NODE_TEXTURE_TRANSFORM,
      TRANSFORM = WB_NODE_TRANSFORM,
      VIEWPOINT = WB_NODE_VIEWPOINT,
      ROBOT = WB_NODE_ROBOT,
      ACCELEROMETER = WB_NODE_ACCELEROMETER,
      ALTIMETER = WB_NODE_ALTIMETER,
      BRAKE = WB_NODE_BRAKE,
      CAMERA = WB_NODE_CAMERA,
      COMPASS = WB_NODE_COMPASS,
      CONNECTOR = WB_NODE_CONNECTOR,
      DISPLAY = WB_NODE_DISPLAY,
      DISTANCE_SENSOR = WB_NODE_DISTANCE_SENSOR,
      EMITTER = WB_NODE_EMITTER,
      GPS = WB_NODE_GPS,
      GYRO = WB_NODE_GYRO,
      INERTIAL_UNIT = WB_NODE_INERTIAL_UNIT,
      LED = WB_NODE_LED,
      LIDAR = WB_NODE_LIDAR,
      LIGHT_SENSOR = WB_NODE_LIGHT_SENSOR,
      LINEAR_MOTOR = WB_NODE_LINEAR_MOTOR,
      PEN = WB_NODE_PEN,
      POSITION_SENSOR = WB_NODE_POSITION_SENSOR,
      PROPELLER = WB_NODE_PROPELLER,
      RADAR = WB_NODE_RADAR,
      RANGE_FINDER = WB_NODE_RANGE_FINDER,
      RECEIVER = WB_NODE_RECEIVER,
      ROTATIONAL_MOTOR = WB_NODE_ROTATIONAL_MOTOR,
      SKIN = WB_NODE_SKIN,
      SPEAKER = WB_NODE_SPEAKER,
      TOUCH_SENSOR = WB_NODE_TOUCH_SENSOR,
      VACUUM_GRIPPER = WB_NODE_VACUUM_GRIPPER,
      BALL_JOINT = WB_NODE_BALL_JOINT,
      BALL_JOINT_PARAMETERS = WB_NODE_BALL_JOINT_PARAMETERS,
      CHARGER = WB_NODE_CHARGER,
      CONTACT_PROPERTIES = WB_NODE_CONTACT_PROPERTIES,
      DAMPING = WB_NODE_DAMPING,
      FLUID = WB_NODE_FLUID,
      FOCUS = WB_NODE_FOCUS,
      HINGE_JOINT = WB_NODE_HINGE_JOINT,
      HINGE_JOINT_PARAMETERS = WB_NODE_HINGE_JOINT_PARAMETERS,
      HINGE_2_JOINT = WB_NODE_HINGE_2_JOINT,
      IMMERSION_PROPERTIES = WB_NODE_IMMERSION_PROPERTIES,
      JOINT_PARAMETERS = WB_NODE_JOINT_PARAMETERS,
      LENS = WB_NODE_LENS,
      LENS_FLARE = WB_NODE_LENS_FLARE,
      PHYSICS = WB_NODE_PHYSICS,
      RECOGNITION = WB_NODE_RECOGNITION,
      SLIDER_JOINT = WB_NODE_SLIDER_JOINT,
      SLOT = WB_NODE_SLOT,
      SOLID = WB_NODE_SOLID,
      SOLID_REFERENCE = WB_NODE_SOLID_REFERENCE,
      TRACK = WB_NODE_TRACK,
      TRACK_WHEEL = WB_NODE_TRACK_WHEEL,
      WORLD_INFO = WB_NODE_WORLD_INFO,
      ZOOM = WB_NODE_ZOOM,
      MICROPHONE = WB_NODE_MICROPHONE,
      RADIO = WB_NODE_RADIO
    };
    // The Node of a C reference (NULL for NULL).
    static Node *findNode(WbNodeRef ref) {
      if (!ref)
        return 0;
      std::map<WbNodeRef, Node *> &known = nodes();
      std::map<WbNodeRef, Node *>::iterator found = known.find(ref);
      if (found != known.end())
        return found->second;
      Node *made = new Node(ref);
      known[ref] = made;
      return made;
    }
    int getId() const { return wb_supervisor_node_get_id(ref); }
    std::string getDef() const { return wb_supervisor_node_get_def(ref); }
    std::string getTypeName() const { return wb_supervisor_node_get_type_name(ref); }
    std::string getBaseTypeName() const { return wb_supervisor_node_get_base_type_name(ref); }
    Type getType() const { return static_cast<Type>(wb_supervisor_node_get_type(ref)); }
    bool isProto() const { return wb_supervisor_node_is_proto(ref); }
    Node *getParentNode() const { return findNode(wb_supervisor_node_get_parent_node(ref)); }
    Field *getField(const std::string &fieldName) const {
      return Field::findField(wb_supervisor_node_get_field(ref, fieldName.c_str()));
    }
    Field *getProtoField(const std::string &fieldName) const {
      return Field::findField(wb_supervisor_node_get_proto_field(ref, fieldName.c_str()));
    }
    Field *getFieldByIndex(int index) const {
      return Field::findField(wb_supervisor_node_get_field_by_index(ref, index));
    }
    int getNumberOfFields() const { return wb_supervisor_node_get_number_of_fields(ref); }
    const double *getPosition() const { return wb_supervisor_node_get_position(ref); }
    const double *getOrientation() const { return wb_supervisor_node_get_orientation(ref); }
    const double *getPose() const { return wb_supervisor_node_get_pose(ref, 0); }
    const double *getPose(const Node *fromNode) const {
      return wb_supervisor_node_get_pose(ref, fromNode ? fromNode->ref : 0);
    }
    const double *getCenterOfMass() const { return wb_supervisor_node_get_center_of_mass(ref); }
    const double *getVelocity() const { return wb_supervisor_node_get_velocity(ref); }
    void setVelocity(const double velocity[6]) { wb_supervisor_node_set_velocity(ref, velocity); }
    void resetPhysics() { wb_supervisor_node_reset_physics(ref); }
    void restartController() { wb_supervisor_node_restart_controller(ref); }
    bool getStaticBalance() const { return wb_supervisor_node_get_static_balance(ref); }
    void remove() { wb_supervisor_node_remove(ref); }
    ContactPoint *getContactPoints(bool includeDescendants, int *size) const {
      return wb_supervisor_node_get_contact_points(ref, includeDescendants, size);
    }

  private:
    explicit Node(WbNodeRef ref) : ref(ref) {}
    static std::map<WbNodeRef, Node *> &nodes() {
      static std::map<WbNodeRef, Node *> known;
      return known;
    }
    WbNodeRef ref;
  };

  Node *Field::getSFNode() const { return Node::findNode(wb_supervisor_field_get_sf_node(ref)); }
  Node *Field::getMFNode(int index) const {
    return Node::findNode(wb_supervisor_field_get_mf_node(ref, index));
  }
}  // namespace webots

#endif
