#include <osgActor/core/skin/SkinBinding>

#include <sstream>

namespace osgActor {

SkinBinding bindSkinToDefinition(const Skin& skin, const ActorDefinition& definition)
{
    SkinBinding binding;
    binding.definitionJoints.reserve(skin.getNumJoints());
    for (unsigned j = 0; j < skin.getNumJoints(); ++j)
    {
        const int found = definition.findJoint(skin.getJointName(j));
        if (found < 0)
        {
            std::ostringstream what;
            what << "skin '" << skin.getName() << "': joint " << j << " '" << skin.getJointName(j)
                 << "' is not a joint of actor '" << definition.getName() << "'";
            SkinBinding refused;
            refused.error = what.str();
            refused.errorJoint = static_cast<int>(j);
            return refused;
        }
        binding.definitionJoints.push_back(static_cast<std::uint32_t>(found));
    }
    return binding;
}

} // namespace osgActor
