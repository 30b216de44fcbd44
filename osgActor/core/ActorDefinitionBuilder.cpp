#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/detail/JointChildren.h>
#include <osgActor/core/detail/NameIndex>

#include <glm/ext/matrix_transform.hpp>
#include <glm/ext/quaternion_geometric.hpp>
#include <glm/ext/quaternion_trigonometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string_view>

namespace osgActor {

namespace {

bool isFinite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string quoted(const std::string& name) { return "'" + name + "'"; }

/** Says what is wrong with one DOF's description, or returns an empty string. */
std::string checkDof(const JointSpec& joint, Dof dof)
{
    const DofSpec& spec = joint.dofs[static_cast<unsigned>(dof)];
    const bool valid = !std::isnan(spec.min) && !std::isnan(spec.max) && spec.min <= spec.max &&
                       std::isfinite(spec.defaultValue) && std::abs(spec.defaultValue) <= kMaxDofMagnitude &&
                       spec.defaultValue >= spec.min && spec.defaultValue <= spec.max && std::isfinite(spec.weight) &&
                       spec.weight >= 0.0;
    // The message is made only for a DOF that has something wrong: every joint of every file is checked here.
    if (!spec.active || valid) return std::string();
    std::ostringstream what;
    const std::string name = quoted(joint.name + "." + dofName(dof));
    if (std::isnan(spec.min) || std::isnan(spec.max))
        what << "DOF " << name << " has a NaN limit";
    else if (spec.min > spec.max)
        what << "DOF " << name << " has its minimum " << spec.min << " above its maximum " << spec.max;
    else if (!std::isfinite(spec.defaultValue))
        what << "DOF " << name << " has a non-finite default value";
    else if (std::abs(spec.defaultValue) > kMaxDofMagnitude)
        what << "DOF " << name << " has its default value " << spec.defaultValue << " beyond +-" << kMaxDofMagnitude;
    else if (spec.defaultValue < spec.min || spec.defaultValue > spec.max)
        what << "DOF " << name << " has its default value " << spec.defaultValue << " outside its limits ["
             << spec.min << ", " << spec.max << "]";
    else if (!std::isfinite(spec.weight) || spec.weight < 0.0)
        what << "DOF " << name << " has weight " << spec.weight << "; weights must be finite and >= 0";
    return what.str();
}

/** Says what is wrong with one joint in isolation, or returns an empty string. */
std::string checkJoint(const JointSpec& joint)
{
    if (joint.name.empty()) return "a joint has an empty name";
    if (!isFinite(joint.translation)) return "joint " + quoted(joint.name) + " has a non-finite offset";
    if (std::max({std::abs(joint.translation.x), std::abs(joint.translation.y), std::abs(joint.translation.z)}) >
        kMaxDofMagnitude)
    {
        std::ostringstream what;
        what << "joint " << quoted(joint.name) << " has an offset beyond +-" << kMaxDofMagnitude;
        return what.str();
    }
    const glm::dquat& q = joint.rotation;
    const double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (!std::isfinite(norm) || norm < 1e-12)
        return "joint " + quoted(joint.name) + " has a zero or non-finite offset rotation";
    for (unsigned d = 0; d < kNumDofTypes; ++d)
    {
        const std::string error = checkDof(joint, static_cast<Dof>(d));
        if (!error.empty()) return error;
    }
    return std::string();
}

/** Parent-first order of the joints: depth first from each root, children in the order they were added. Joints
  * left out of the order hang below a parent cycle. */
std::vector<unsigned> parentFirstOrder(const std::vector<int>& parents)
{
    const detail::JointChildren children(parents);
    std::vector<unsigned> order;
    order.reserve(parents.size());
    std::vector<unsigned> stack;
    for (unsigned j = static_cast<unsigned>(parents.size()); j-- > 0;)
        if (parents[j] < 0) stack.push_back(j);
    while (!stack.empty())
    {
        const unsigned j = stack.back();
        stack.pop_back();
        order.push_back(j);
        const Span<const unsigned> below = children.of(j);
        for (std::size_t c = below.size(); c-- > 0;) stack.push_back(below[c]);
    }
    return order;
}

/** Describes the parent cycle above joint start ("a -> b -> a"). */
std::string describeCycle(const JointSpecList& joints, const std::vector<int>& parents, unsigned start)
{
    // Walk up until a joint repeats; that joint is on the cycle.
    std::vector<bool> seen(joints.size(), false);
    unsigned j = start;
    while (!seen[j])
    {
        seen[j] = true;
        j = static_cast<unsigned>(parents[j]);
    }
    std::string text = quoted(joints[j].name);
    for (unsigned k = static_cast<unsigned>(parents[j]);; k = static_cast<unsigned>(parents[k]))
    {
        text += " -> " + quoted(joints[k].name);
        if (k == j) break;
    }
    return text;
}

JointKinematics makeKinematics(const JointSpec& joint, unsigned firstDof, DofMask mask)
{
    JointKinematics k;
    const glm::dquat rotation = glm::normalize(joint.rotation);
    k.offset = glm::translate(glm::dmat4(1.0), joint.translation) * glm::mat4_cast(rotation);
    k.offsetIsTranslation = rotation.w == 1.0 || rotation.w == -1.0;
    k.translationMode = joint.translationMode;

    // Absolute index of each active DOF, in the vector's rx..tz order.
    int dofIndex[kNumDofTypes];
    unsigned next = firstDof;
    for (unsigned d = 0; d < kNumDofTypes; ++d) dofIndex[d] = (mask & (1u << d)) ? static_cast<int>(next++) : -1;

    unsigned axes[3];
    eulerOrderAxes(joint.eulerOrder, axes);
    for (unsigned axis : axes)
    {
        if (dofIndex[axis] < 0) continue; // an inactive rotation costs nothing
        k.rotationDof[k.numRotations] = static_cast<std::uint32_t>(dofIndex[axis]);
        k.rotationAxis[k.numRotations] = static_cast<std::uint8_t>(axis);
        ++k.numRotations;
    }
    for (unsigned t = 0; t < 3; ++t) k.translationDof[t] = dofIndex[3 + t];
    k.hasTranslation = (mask & kTranslationDofs) != 0;
    k.rotationSequence = rotationSequenceOf(k.numRotations, k.rotationAxis);
    return k;
}

} // namespace

ActorDefinitionBuilder::JointRef& ActorDefinitionBuilder::JointRef::rotation(double angle, double axisX,
                                                                             double axisY, double axisZ)
{
    const glm::dvec3 axis(axisX, axisY, axisZ);
    const double length = std::sqrt(axisX * axisX + axisY * axisY + axisZ * axisZ);
    // A zero axis leaves a zero quaternion, which build() refuses with a message naming the joint.
    spec().rotation = length > 0.0 ? glm::angleAxis(angle, axis / length) : glm::dquat(0.0, 0.0, 0.0, 0.0);
    return *this;
}

ActorDefinitionBuilder::JointRef& ActorDefinitionBuilder::JointRef::dofs(DofMask mask)
{
    for (unsigned d = 0; d < kNumDofTypes; ++d) spec().dofs[d].active = (mask & (1u << d)) != 0;
    return *this;
}

ActorDefinitionBuilder::JointRef& ActorDefinitionBuilder::JointRef::limits(Dof dof, double min, double max)
{
    DofSpec& d = spec().dofs[static_cast<unsigned>(dof)];
    d.min = min;
    d.max = max;
    return *this;
}

ActorDefinitionBuilder::JointRef& ActorDefinitionBuilder::JointRef::defaultValue(Dof dof, double value)
{
    spec().dofs[static_cast<unsigned>(dof)].defaultValue = value;
    return *this;
}

ActorDefinitionBuilder::JointRef& ActorDefinitionBuilder::JointRef::weight(Dof dof, double weight)
{
    spec().dofs[static_cast<unsigned>(dof)].weight = weight;
    return *this;
}

JointSpec& ActorDefinitionBuilder::JointRef::spec() { return _builder->_joints[_index]; }

ActorDefinitionBuilder::JointRef ActorDefinitionBuilder::addJoint(const std::string& name,
                                                                  const std::string& parent)
{
    JointSpec spec;
    spec.name = name;
    spec.parent = parent;
    return addJoint(spec);
}

ActorDefinitionBuilder::JointRef ActorDefinitionBuilder::addJoint(const JointSpec& spec)
{
    _joints.push_back(spec);
    return JointRef(*this, static_cast<unsigned>(_joints.size() - 1));
}

BuildResult ActorDefinitionBuilder::build() const { return buildFrom(_name, JointSpecList(_joints)); }

BuildResult ActorDefinitionBuilder::buildFrom(const std::string& name, const JointSpecList& joints)
{
    BuildResult result;
    const std::string actor = name.empty() ? std::string("actor") : "actor " + quoted(name);
    auto fail = [&](const std::string& message, int joint = -1) {
        result.error = actor + ": " + message;
        result.errorJoint = joint;
        return result;
    };

    if (joints.empty()) return fail("has no joints");

    // One index of the joints' own names (no copy of a name, no allocation per name), then one visit per joint that
    // checks it, finds its parent and counts its DOFs: a large actor's joints do not fit the caches, and every
    // further pass over them would fetch them again. A name given twice is found at its first place.
    const auto nameOf = [&joints](std::size_t j) -> std::string_view { return joints[j].name; };
    NameIndex byName;
    byName.build(joints.size(), nameOf);
    std::vector<int> parents(joints.size(), kNoParent);
    std::size_t numDofs = 0;
    int unknownParent = -1; // the first joint whose parent is no joint: reported after the joints' own errors
    for (unsigned j = 0; j < joints.size(); ++j)
    {
        const JointSpec& joint = joints[j];
        const std::string error = checkJoint(joint);
        if (!error.empty()) return fail(error, static_cast<int>(j));
        if (byName.find(joint.name, nameOf) != static_cast<int>(j))
            return fail("joint name " + quoted(joint.name) + " is used twice", static_cast<int>(j));
        for (const DofSpec& dof : joint.dofs) numDofs += dof.active ? 1u : 0u;
        if (joint.parent.empty()) continue;
        parents[j] = byName.find(joint.parent, nameOf);
        if (parents[j] < 0 && unknownParent < 0) unknownParent = static_cast<int>(j);
    }
    if (unknownParent >= 0)
    {
        const JointSpec& joint = joints[static_cast<unsigned>(unknownParent)];
        return fail("joint " + quoted(joint.name) + " names an unknown parent " + quoted(joint.parent), unknownParent);
    }

    const std::vector<unsigned> order = parentFirstOrder(parents);
    if (order.size() != joints.size())
    {
        std::vector<bool> placed(joints.size(), false);
        for (unsigned j : order) placed[j] = true;
        unsigned stray = 0;
        while (placed[stray]) ++stray;
        return fail("the joints form a parent cycle: " + describeCycle(joints, parents, stray),
                    static_cast<int>(stray));
    }

    // Depth of each joint, the root's being 1: its parent's plus one, the parent coming first in the order.
    std::vector<unsigned> depths(joints.size(), 1);
    for (unsigned j : order)
    {
        if (parents[j] >= 0) depths[j] = depths[static_cast<unsigned>(parents[j])] + 1;
        if (depths[j] > kMaxJointDepth)
            return fail("joint " + quoted(joints[j].name) + " is " + std::to_string(depths[j]) +
                            " joints deep (its root included); a skeleton may be at most " +
                            std::to_string(kMaxJointDepth) + " deep",
                        static_cast<int>(j));
    }

    std::shared_ptr<ActorDefinition> def(new ActorDefinition());
    def->_name = name;
    std::vector<int> newIndex(joints.size(), -1);
    for (unsigned i = 0; i < order.size(); ++i) newIndex[order[i]] = static_cast<int>(i);

    // Every per-joint and per-DOF array at its final size at once, rather than grown a joint at a time.
    const std::size_t numJoints = joints.size();
    def->_jointNames.reserve(numJoints);
    def->_parents.reserve(numJoints);
    def->_offsetTranslations.reserve(numJoints);
    def->_offsetRotations.reserve(numJoints);
    def->_eulerOrders.reserve(numJoints);
    def->_dofMasks.reserve(numJoints);
    def->_firstDofs.reserve(numJoints + 1);
    def->_kinematics.reserve(numJoints);
    for (std::vector<double>* perDof : {&def->_dofMins, &def->_dofMaxs, &def->_dofRangeMins, &def->_dofRangeMaxs,
                                        &def->_dofDefaults, &def->_dofWeights})
        perDof->reserve(numDofs);
    def->_dofJoints.reserve(numDofs);
    def->_dofTypes.reserve(numDofs);
    def->_firstDofs.push_back(0);
    for (unsigned i = 0; i < order.size(); ++i)
    {
        const JointSpec& joint = joints[order[i]];
        const int oldParent = parents[order[i]];
        DofMask mask = 0;
        for (unsigned d = 0; d < kNumDofTypes; ++d)
        {
            const DofSpec& dof = joint.dofs[d];
            if (!dof.active) continue;
            mask = static_cast<DofMask>(mask | (1u << d));
            def->_dofJoints.push_back(i);
            def->_dofTypes.push_back(static_cast<Dof>(d));
            def->_dofMins.push_back(dof.min);
            def->_dofMaxs.push_back(dof.max);
            def->_dofRangeMins.push_back(std::min(std::max(dof.min, -kMaxDofMagnitude), kMaxDofMagnitude));
            def->_dofRangeMaxs.push_back(std::max(std::min(dof.max, kMaxDofMagnitude), -kMaxDofMagnitude));
            def->_dofDefaults.push_back(dof.defaultValue);
            def->_dofWeights.push_back(dof.weight);
        }
        def->_jointNames.push_back(joint.name);
        def->_parents.push_back(oldParent < 0 ? kNoParent : newIndex[static_cast<unsigned>(oldParent)]);
        def->_offsetTranslations.push_back(joint.translation);
        def->_offsetRotations.push_back(glm::normalize(joint.rotation));
        def->_eulerOrders.push_back(joint.eulerOrder);
        def->_dofMasks.push_back(mask);
        def->_kinematics.push_back(makeKinematics(joint, def->_firstDofs.back(), mask));
        def->_firstDofs.push_back(static_cast<unsigned>(def->_dofJoints.size()));
    }
    // The joints kept their places (a file that gives parents first, as most do): the index of their names is the
    // definition's.
    bool samePlaces = true;
    for (unsigned i = 0; i < order.size() && samePlaces; ++i) samePlaces = order[i] == i;
    if (samePlaces) def->_jointIndex = std::move(byName);
    else def->_jointIndex.build(def->_jointNames);
    def->_jointBatches = planJointBatches(def->_kinematics);
    result.definition = def;
    return result;
}

JointSpec toJointSpec(const ActorDefinition& definition, unsigned joint)
{
    JointSpec spec;
    spec.name = definition.getJointName(joint);
    const int parent = definition.getParent(joint);
    if (parent >= 0) spec.parent = definition.getJointName(static_cast<unsigned>(parent));
    spec.translation = definition.getOffsetTranslation(joint);
    spec.rotation = definition.getOffsetRotation(joint);
    spec.eulerOrder = definition.getEulerOrder(joint);
    spec.translationMode = definition.getTranslationMode(joint);
    for (unsigned d = 0; d < kNumDofTypes; ++d)
    {
        const int index = definition.getDofIndex(joint, static_cast<Dof>(d));
        if (index < 0) continue;
        const unsigned i = static_cast<unsigned>(index);
        spec.dofs[d] = DofSpec{true, definition.getDofMin(i), definition.getDofMax(i), definition.getDofDefault(i),
                               definition.getDofWeight(i)};
    }
    return spec;
}

ActorDefinitionBuilder toBuilder(const ActorDefinition& definition)
{
    ActorDefinitionBuilder builder(definition.getName());
    builder.reserve(definition.getNumJoints());
    for (unsigned j = 0; j < definition.getNumJoints(); ++j) builder.addJoint(toJointSpec(definition, j));
    return builder;
}

} // namespace osgActor
