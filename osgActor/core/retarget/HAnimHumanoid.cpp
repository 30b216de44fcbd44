#include <osgActor/core/retarget/HAnimHumanoid>

#include <unordered_map>
#include <vector>

namespace osgActor {

namespace {

/** The hierarchy as the standard draws it, a joint's parent by name (parents first). */
struct JointRow
{
    const char* name;
    const char* parent;
    unsigned char levelOfArticulation;
};

// clang-format off
const JointRow kRows[] = {
    {"HumanoidRoot", nullptr, 0},
    {"sacroiliac", "HumanoidRoot", 1},
    {"l_hip", "sacroiliac", 1}, {"l_knee", "l_hip", 1}, {"l_ankle", "l_knee", 1},
    {"l_subtalar", "l_ankle", 2}, {"l_midtarsal", "l_subtalar", 1}, {"l_metatarsal", "l_midtarsal", 2},
    {"r_hip", "sacroiliac", 1}, {"r_knee", "r_hip", 1}, {"r_ankle", "r_knee", 1},
    {"r_subtalar", "r_ankle", 2}, {"r_midtarsal", "r_subtalar", 1}, {"r_metatarsal", "r_midtarsal", 2},
    // The spine from the lowest lumbar vertebra up: 5 lumbar, 12 thoracic, 7 cervical.
    {"vl5", "HumanoidRoot", 1}, {"vl4", "vl5", 3}, {"vl3", "vl4", 2}, {"vl2", "vl3", 3}, {"vl1", "vl2", 2},
    {"vt12", "vl1", 3}, {"vt11", "vt12", 3}, {"vt10", "vt11", 2}, {"vt9", "vt10", 3}, {"vt8", "vt9", 3},
    {"vt7", "vt8", 3}, {"vt6", "vt7", 2}, {"vt5", "vt6", 3}, {"vt4", "vt5", 3}, {"vt3", "vt4", 3},
    {"vt2", "vt3", 3}, {"vt1", "vt2", 2},
    {"vc7", "vt1", 3}, {"vc6", "vc7", 3}, {"vc5", "vc6", 3}, {"vc4", "vc5", 2}, {"vc3", "vc4", 3},
    {"vc2", "vc3", 2}, {"vc1", "vc2", 3},
    {"skullbase", "vc1", 1},
    {"l_eyelid_joint", "skullbase", 3}, {"r_eyelid_joint", "skullbase", 3},
    {"l_eyeball_joint", "skullbase", 3}, {"r_eyeball_joint", "skullbase", 3},
    {"l_eyebrow_joint", "skullbase", 3}, {"r_eyebrow_joint", "skullbase", 3},
    {"temporomandibular", "skullbase", 3},
    {"l_sternoclavicular", "vt1", 2}, {"l_acromioclavicular", "l_sternoclavicular", 2},
    {"l_shoulder", "l_acromioclavicular", 1}, {"l_elbow", "l_shoulder", 1}, {"l_wrist", "l_elbow", 1},
    {"l_thumb1", "l_wrist", 2}, {"l_thumb2", "l_thumb1", 2}, {"l_thumb3", "l_thumb2", 2},
    {"l_index0", "l_wrist", 2}, {"l_index1", "l_index0", 2}, {"l_index2", "l_index1", 2}, {"l_index3", "l_index2", 2},
    {"l_middle0", "l_wrist", 2}, {"l_middle1", "l_middle0", 2}, {"l_middle2", "l_middle1", 2},
    {"l_middle3", "l_middle2", 2},
    {"l_ring0", "l_wrist", 2}, {"l_ring1", "l_ring0", 2}, {"l_ring2", "l_ring1", 2}, {"l_ring3", "l_ring2", 2},
    {"l_pinky0", "l_wrist", 2}, {"l_pinky1", "l_pinky0", 2}, {"l_pinky2", "l_pinky1", 2}, {"l_pinky3", "l_pinky2", 2},
    {"r_sternoclavicular", "vt1", 2}, {"r_acromioclavicular", "r_sternoclavicular", 2},
    {"r_shoulder", "r_acromioclavicular", 1}, {"r_elbow", "r_shoulder", 1}, {"r_wrist", "r_elbow", 1},
    {"r_thumb1", "r_wrist", 2}, {"r_thumb2", "r_thumb1", 2}, {"r_thumb3", "r_thumb2", 2},
    {"r_index0", "r_wrist", 2}, {"r_index1", "r_index0", 2}, {"r_index2", "r_index1", 2}, {"r_index3", "r_index2", 2},
    {"r_middle0", "r_wrist", 2}, {"r_middle1", "r_middle0", 2}, {"r_middle2", "r_middle1", 2},
    {"r_middle3", "r_middle2", 2},
    {"r_ring0", "r_wrist", 2}, {"r_ring1", "r_ring0", 2}, {"r_ring2", "r_ring1", 2}, {"r_ring3", "r_ring2", 2},
    {"r_pinky0", "r_wrist", 2}, {"r_pinky1", "r_pinky0", 2}, {"r_pinky2", "r_pinky1", 2}, {"r_pinky3", "r_pinky2", 2},
};
// clang-format on

constexpr unsigned kNumRows = sizeof(kRows) / sizeof(kRows[0]);

/** The table with parent indices, and the name index, built once on first use. */
struct Table
{
    std::vector<HAnimJoint> joints;
    std::vector<int> mirrors;
    std::unordered_map<std::string, int> index;

    Table()
    {
        joints.reserve(kNumRows);
        for (unsigned i = 0; i < kNumRows; ++i)
        {
            const int parent = kRows[i].parent ? index.at(kRows[i].parent) : -1; // parents come first
            joints.push_back(HAnimJoint{kRows[i].name, parent, kRows[i].levelOfArticulation});
            index.emplace(kRows[i].name, static_cast<int>(i));
        }
        mirrors.resize(kNumRows);
        for (unsigned i = 0; i < kNumRows; ++i)
        {
            std::string name = kRows[i].name;
            if (name.size() > 2 && (name[0] == 'l' || name[0] == 'r') && name[1] == '_')
                name[0] = name[0] == 'l' ? 'r' : 'l';
            const auto found = index.find(name);
            mirrors[i] = found != index.end() ? found->second : static_cast<int>(i);
        }
    }
};

const Table& table()
{
    static const Table instance;
    return instance;
}

} // namespace

unsigned getNumHAnimJoints() { return kNumRows; }

const HAnimJoint& getHAnimJoint(unsigned i) { return table().joints[i]; }

int findHAnimJoint(const std::string& name)
{
    const auto& index = table().index;
    const auto found = index.find(name);
    return found != index.end() ? found->second : -1;
}

bool isHAnimAncestor(int ancestor, int joint)
{
    const auto& joints = table().joints;
    if (ancestor < 0 || joint < 0) return false;
    for (int j = joints[joint].parent; j >= 0; j = joints[j].parent)
        if (j == ancestor) return true;
    return false;
}

int mirrorHAnimJoint(int joint) { return table().mirrors[joint]; }

} // namespace osgActor
