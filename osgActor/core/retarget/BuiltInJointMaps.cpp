#include <osgActor/core/retarget/BuiltInJointMaps>
#include <osgActor/core/retarget/HAnimHumanoid>

#include <algorithm>
#include <array>
#include <cctype>

namespace osgActor {

namespace {

/** A row of a convention's table, written once for both sides where it names a sided joint. In the joint name "$s"
  * stands for l or r, "$S" for L or R and "$Side" for Left or Right; in the H-Anim name "$h" stands for l or r. */
struct MapRow
{
    const char* joint;
    const char* hanim;
};

// CMU's ASF skeletons: a bone's joint is where the bone starts (docs/mocap.md), so lfemur is the hip. lwrist (the
// forearm's twist at the wrist) and lhand (the wrist's flexion) are both H-Anim's wrist; lhipjoint, a fixed bone from
// the pelvis's centre to the hip, is none.
const MapRow kCmuAsf[] = {
    {"root", "HumanoidRoot"}, {"lowerback", "vl5"}, {"upperback", "vl1"}, {"thorax", "vt6"},
    {"lowerneck", "vc7"}, {"upperneck", "vc4"}, {"head", "skullbase"},
    {"$sfemur", "$h_hip"}, {"$stibia", "$h_knee"}, {"$sfoot", "$h_ankle"}, {"$stoes", "$h_metatarsal"},
    {"$sclavicle", "$h_sternoclavicular"}, {"$shumerus", "$h_shoulder"}, {"$sradius", "$h_elbow"},
    {"$swrist", "$h_wrist"}, {"$shand", "$h_wrist"}, {"$sfingers", "$h_index1"}, {"$sthumb", "$h_thumb1"},
};

// CMU's BVH conversions: the ASF bones renamed (LHipJoint = lhipjoint, LeftHand = lwrist, LeftFingerBase = lhand),
// LeftShoulder being the clavicle.
const MapRow kCmuBvh[] = {
    {"Hips", "HumanoidRoot"}, {"LowerBack", "vl5"}, {"Spine", "vl1"}, {"Spine1", "vt6"},
    {"Neck", "vc7"}, {"Neck1", "vc4"}, {"Head", "skullbase"},
    {"$SideUpLeg", "$h_hip"}, {"$SideLeg", "$h_knee"}, {"$SideFoot", "$h_ankle"}, {"$SideToeBase", "$h_metatarsal"},
    {"$SideShoulder", "$h_sternoclavicular"}, {"$SideArm", "$h_shoulder"}, {"$SideForeArm", "$h_elbow"},
    {"$SideHand", "$h_wrist"}, {"$SideFingerBase", "$h_wrist"}, {"$SideHandIndex1", "$h_index1"},
    {"$SFingers", "$h_index1"}, {"$SThumb", "$h_thumb1"},
};

// MotionBuilder / Motion Analysis BVH: LeftShoulder is the upper arm, LeftCollar the clavicle, LeftHip the thigh.
const MapRow kMotionBuilderBvh[] = {
    {"Hips", "HumanoidRoot"}, {"Ab", "vl5"}, {"Chest", "vt6"}, {"Chest2", "vt1"}, {"Neck", "vc7"},
    {"Head", "skullbase"},
    {"$SideHip", "$h_hip"}, {"$SideKnee", "$h_knee"}, {"$SideAnkle", "$h_ankle"}, {"$SideToes", "$h_metatarsal"},
    {"$SideCollar", "$h_sternoclavicular"}, {"$SideShoulder", "$h_shoulder"}, {"$SideElbow", "$h_elbow"},
    {"$SideWrist", "$h_wrist"},
};

// Mixamo: names carry a namespace ("mixamorig:", "mixamorig1:"), which loose matching ignores.
const MapRow kMixamo[] = {
    {"mixamorig:Hips", "HumanoidRoot"}, {"mixamorig:Spine", "vl5"}, {"mixamorig:Spine1", "vt10"},
    {"mixamorig:Spine2", "vt6"}, {"mixamorig:Neck", "vc7"}, {"mixamorig:Head", "skullbase"},
    {"mixamorig:$SideUpLeg", "$h_hip"}, {"mixamorig:$SideLeg", "$h_knee"}, {"mixamorig:$SideFoot", "$h_ankle"},
    {"mixamorig:$SideToeBase", "$h_metatarsal"},
    {"mixamorig:$SideShoulder", "$h_sternoclavicular"}, {"mixamorig:$SideArm", "$h_shoulder"},
    {"mixamorig:$SideForeArm", "$h_elbow"}, {"mixamorig:$SideHand", "$h_wrist"},
    {"mixamorig:$SideHandThumb1", "$h_thumb1"}, {"mixamorig:$SideHandThumb2", "$h_thumb2"},
    {"mixamorig:$SideHandThumb3", "$h_thumb3"},
    {"mixamorig:$SideHandIndex1", "$h_index1"}, {"mixamorig:$SideHandIndex2", "$h_index2"},
    {"mixamorig:$SideHandIndex3", "$h_index3"},
    {"mixamorig:$SideHandMiddle1", "$h_middle1"}, {"mixamorig:$SideHandMiddle2", "$h_middle2"},
    {"mixamorig:$SideHandMiddle3", "$h_middle3"},
    {"mixamorig:$SideHandRing1", "$h_ring1"}, {"mixamorig:$SideHandRing2", "$h_ring2"},
    {"mixamorig:$SideHandRing3", "$h_ring3"},
    {"mixamorig:$SideHandPinky1", "$h_pinky1"}, {"mixamorig:$SideHandPinky2", "$h_pinky2"},
    {"mixamorig:$SideHandPinky3", "$h_pinky3"},
};

// MakeHuman's default skeleton: twist joints (upperleg02, lowerarm02, ...) share their bone's H-Anim joint; finger1 is
// the thumb and metacarpalN carries finger N+1; pelvis.L (the pelvis's centre to the hip) and the toes are none.
const MapRow kMakeHuman[] = {
    {"root", "HumanoidRoot"}, {"spine05", "vl5"}, {"spine04", "vl3"}, {"spine03", "vl1"}, {"spine02", "vt6"},
    {"spine01", "vt1"}, {"neck01", "vc7"}, {"neck02", "vc4"}, {"neck03", "vc2"}, {"head", "skullbase"},
    {"upperleg01.$S", "$h_hip"}, {"upperleg02.$S", "$h_hip"}, {"lowerleg01.$S", "$h_knee"},
    {"lowerleg02.$S", "$h_knee"}, {"foot.$S", "$h_ankle"},
    {"clavicle.$S", "$h_sternoclavicular"}, {"shoulder01.$S", "$h_acromioclavicular"},
    {"upperarm01.$S", "$h_shoulder"}, {"upperarm02.$S", "$h_shoulder"}, {"lowerarm01.$S", "$h_elbow"},
    {"lowerarm02.$S", "$h_elbow"}, {"wrist.$S", "$h_wrist"},
    {"finger1-1.$S", "$h_thumb1"}, {"finger1-2.$S", "$h_thumb2"}, {"finger1-3.$S", "$h_thumb3"},
    {"metacarpal1.$S", "$h_index0"}, {"finger2-1.$S", "$h_index1"}, {"finger2-2.$S", "$h_index2"},
    {"finger2-3.$S", "$h_index3"},
    {"metacarpal2.$S", "$h_middle0"}, {"finger3-1.$S", "$h_middle1"}, {"finger3-2.$S", "$h_middle2"},
    {"finger3-3.$S", "$h_middle3"},
    {"metacarpal3.$S", "$h_ring0"}, {"finger4-1.$S", "$h_ring1"}, {"finger4-2.$S", "$h_ring2"},
    {"finger4-3.$S", "$h_ring3"},
    {"metacarpal4.$S", "$h_pinky0"}, {"finger5-1.$S", "$h_pinky1"}, {"finger5-2.$S", "$h_pinky2"},
    {"finger5-3.$S", "$h_pinky3"},
};

// ISO/IEC 19774-1:2019's names for joints the 2006 edition already had (the H-Anim map adds every 2006 name too).
const MapRow kHAnim2019[] = {
    {"humanoid_root", "HumanoidRoot"}, {"$h_talocrural", "$h_ankle"},
    {"$h_talocalcaneonavicular", "$h_subtalar"}, {"$h_tarsometatarsal", "$h_midtarsal"},
    {"$h_metatarsophalangeal", "$h_metatarsal"}, {"$h_radiocarpal", "$h_wrist"},
    {"$h_carpometacarpal_1", "$h_thumb1"}, {"$h_metacarpophalangeal_1", "$h_thumb2"},
    {"$h_carpal_interphalangeal_1", "$h_thumb3"},
    {"$h_carpometacarpal_2", "$h_index0"}, {"$h_metacarpophalangeal_2", "$h_index1"},
    {"$h_carpal_proximal_interphalangeal_2", "$h_index2"}, {"$h_carpal_distal_interphalangeal_2", "$h_index3"},
    {"$h_carpometacarpal_3", "$h_middle0"}, {"$h_metacarpophalangeal_3", "$h_middle1"},
    {"$h_carpal_proximal_interphalangeal_3", "$h_middle2"}, {"$h_carpal_distal_interphalangeal_3", "$h_middle3"},
    {"$h_carpometacarpal_4", "$h_ring0"}, {"$h_metacarpophalangeal_4", "$h_ring1"},
    {"$h_carpal_proximal_interphalangeal_4", "$h_ring2"}, {"$h_carpal_distal_interphalangeal_4", "$h_ring3"},
    {"$h_carpometacarpal_5", "$h_pinky0"}, {"$h_metacarpophalangeal_5", "$h_pinky1"},
    {"$h_carpal_proximal_interphalangeal_5", "$h_pinky2"}, {"$h_carpal_distal_interphalangeal_5", "$h_pinky3"},
};

/** text with each placeholder replaced for one side (0 left, 1 right). */
std::string forSide(const char* text, unsigned side)
{
    static const char* const kPlaceholders[][3] = {
        {"$Side", "Left", "Right"}, {"$s", "l", "r"}, {"$S", "L", "R"}, {"$h", "l", "r"}};
    std::string result = text;
    for (const auto& placeholder : kPlaceholders)
        for (std::size_t at = result.find(placeholder[0]); at != std::string::npos;
             at = result.find(placeholder[0], at))
        {
            result.replace(at, std::char_traits<char>::length(placeholder[0]), placeholder[1 + side]);
            at += std::char_traits<char>::length(placeholder[1 + side]);
        }
    return result;
}

template <std::size_t N>
void addRows(JointMap& map, const MapRow (&rows)[N])
{
    for (const MapRow& row : rows)
    {
        const bool sided = std::char_traits<char>::find(row.joint, std::char_traits<char>::length(row.joint), '$');
        for (unsigned side = 0; side < (sided ? 2u : 1u); ++side)
            map.add(forSide(row.joint, side), forSide(row.hanim, side));
    }
}

JointMap makeMap(JointMapStyle style)
{
    JointMap map(jointMapStyleName(style));
    map.setLooseMatching(true);
    switch (style)
    {
    case JointMapStyle::HAnim:
        for (unsigned i = 0; i < getNumHAnimJoints(); ++i) map.add(getHAnimJoint(i).name, getHAnimJoint(i).name);
        addRows(map, kHAnim2019);
        break;
    case JointMapStyle::CmuAsf: addRows(map, kCmuAsf); break;
    case JointMapStyle::CmuBvh: addRows(map, kCmuBvh); break;
    case JointMapStyle::MotionBuilderBvh: addRows(map, kMotionBuilderBvh); break;
    case JointMapStyle::Mixamo: addRows(map, kMixamo); break;
    case JointMapStyle::MakeHuman: addRows(map, kMakeHuman); break;
    }
    return map;
}

const char* const kStyleNames[kNumJointMapStyles] = {"hanim",  "cmu_asf", "cmu_bvh", "motionbuilder_bvh",
                                                     "mixamo", "makehuman"};

} // namespace

const JointMap& builtInJointMap(JointMapStyle style)
{
    static const std::array<JointMap, kNumJointMapStyles> maps = [] {
        std::array<JointMap, kNumJointMapStyles> made;
        for (unsigned s = 0; s < kNumJointMapStyles; ++s) made[s] = makeMap(static_cast<JointMapStyle>(s));
        return made;
    }();
    return maps[static_cast<unsigned>(style)];
}

const char* jointMapStyleName(JointMapStyle style) { return kStyleNames[static_cast<unsigned>(style)]; }

bool parseJointMapStyle(const std::string& text, JointMapStyle& style)
{
    std::string lowered = text;
    std::transform(lowered.begin(), lowered.end(), lowered.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    for (unsigned s = 0; s < kNumJointMapStyles; ++s)
        if (lowered == kStyleNames[s])
        {
            style = static_cast<JointMapStyle>(s);
            return true;
        }
    return false;
}

} // namespace osgActor
