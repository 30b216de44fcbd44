#include <osgActor/core/ActorDefinition>

namespace osgActor {

int ActorDefinition::findJoint(const std::string& name) const
{
    return _jointIndex.find(name, _jointNames);
}

int ActorDefinition::getDofIndex(unsigned joint, Dof dof) const
{
    const DofMask mask = _dofMasks[joint];
    const DofMask bit = dofBit(dof);
    if ((mask & bit) == 0) return -1;
    // Active DOFs are stored in rx..tz order, so the DOF's slot is the count of active bits below it.
    const DofMask below = static_cast<DofMask>(mask & (bit - 1u));
    unsigned slot = 0;
    for (DofMask m = below; m != 0; m = static_cast<DofMask>(m & (m - 1u))) ++slot;
    return static_cast<int>(_firstDofs[joint] + slot);
}

std::string ActorDefinition::getDofName(unsigned dof) const
{
    return _jointNames[_dofJoints[dof]] + "." + dofName(_dofTypes[dof]);
}

int ActorDefinition::findDof(const std::string& name) const
{
    const std::string::size_type dot = name.rfind('.');
    if (dot == std::string::npos) return -1;
    Dof type;
    if (!parseDof(name.substr(dot + 1), type)) return -1;
    const int joint = findJoint(name.substr(0, dot));
    if (joint < 0) return -1;
    return getDofIndex(static_cast<unsigned>(joint), type);
}

} // namespace osgActor
