#include "BenchHumanoid"

#include <osgActor/core/ActorDefinitionBuilder>
#include <osgActor/core/ClipBuilder>

#include <cmath>

namespace bench {

const std::vector<BenchJoint>& humanoidJoints()
{
    static const std::vector<BenchJoint> joints = {
        {"hips", -1, {0, 0, 1.0}},
        {"lhipjoint", 0, {0.1, 0, -0.05}}, {"lfemur", 1, {0, 0, -0.05}}, {"ltibia", 2, {0, 0, -0.42}},
        {"lfoot", 3, {0, 0, -0.42}}, {"ltoes", 4, {0, -0.12, -0.05}},
        {"rhipjoint", 0, {-0.1, 0, -0.05}}, {"rfemur", 6, {0, 0, -0.05}}, {"rtibia", 7, {0, 0, -0.42}},
        {"rfoot", 8, {0, 0, -0.42}}, {"rtoes", 9, {0, -0.12, -0.05}},
        {"lowerback", 0, {0, 0, 0.1}}, {"upperback", 11, {0, 0, 0.12}}, {"thorax", 12, {0, 0, 0.12}},
        {"lowerneck", 13, {0, 0, 0.12}}, {"upperneck", 14, {0, 0, 0.06}}, {"head", 15, {0, 0, 0.08}},
        {"lclavicle", 13, {0.05, 0, 0.08}}, {"lhumerus", 17, {0.15, 0, 0}}, {"lradius", 18, {0.28, 0, 0}},
        {"lwrist", 19, {0.25, 0, 0}}, {"lhand", 20, {0.05, 0, 0}}, {"lfingers", 21, {0.06, 0, 0}},
        {"lthumb", 20, {0.03, -0.03, 0}},
        {"rclavicle", 13, {-0.05, 0, 0.08}}, {"rhumerus", 24, {-0.15, 0, 0}}, {"rradius", 25, {-0.28, 0, 0}},
        {"rwrist", 26, {-0.25, 0, 0}}, {"rhand", 27, {-0.05, 0, 0}}, {"rfingers", 28, {-0.06, 0, 0}},
        {"rthumb", 27, {-0.03, -0.03, 0}},
    };
    return joints;
}

const BenchClip& humanoidClip()
{
    static const BenchClip clip = [] {
        BenchClip c;
        c.numFrames = 61;
        c.jointCount = static_cast<unsigned>(humanoidJoints().size());
        c.angles.resize(c.numFrames * c.jointCount * 3);
        c.rootPosition.resize(c.numFrames * 3);
        for (unsigned f = 0; f < c.numFrames; ++f)
        {
            const double phase = 2.0 * M_PI * f / (c.numFrames - 1);
            for (unsigned j = 0; j < c.jointCount; ++j)
                for (unsigned a = 0; a < 3; ++a)
                    c.angles[(f * c.jointCount + j) * 3 + a] = (0.5 / (a + 1)) * std::sin(phase + 0.37 * j + a);
            c.rootPosition[f * 3 + 0] = 0.02 * std::sin(phase);
            c.rootPosition[f * 3 + 1] = 0.8 * f / (c.numFrames - 1);
            c.rootPosition[f * 3 + 2] = 0.03 * std::sin(2.0 * phase);
        }
        return c;
    }();
    return clip;
}

osgActor::ActorDefinitionPtr humanoidDefinition()
{
    using namespace osgActor;
    ActorDefinitionBuilder builder("bench_humanoid");
    const std::vector<BenchJoint>& joints = humanoidJoints();
    for (const BenchJoint& joint : joints)
    {
        const std::string parent = joint.parent < 0 ? std::string() : joints[joint.parent].name;
        auto ref = builder.addJoint(joint.name, parent).offset(joint.offset[0], joint.offset[1], joint.offset[2]);
        if (joint.parent < 0)
            ref.dofs(kRotationDofs | Dof::TX | Dof::TY | Dof::TZ).translationMode(TranslationMode::BeforeRotation);
        else
            ref.dofs(kRotationDofs);
    }
    return builder.build().definition;
}

osgActor::ClipPtr humanoidOsgActorClip()
{
    static const osgActor::ClipPtr clip = [] {
        const BenchClip& bench = humanoidClip();
        const std::vector<BenchJoint>& joints = humanoidJoints();
        osgActor::ClipBuilder builder("bench");
        static const char* const rotations[] = {".rx", ".ry", ".rz"};
        static const char* const translations[] = {".tx", ".ty", ".tz"};
        for (unsigned j = 0; j < joints.size(); ++j)
        {
            for (const char* dof : rotations) builder.addChannel(joints[j].name + dof);
            if (j == 0)
                for (const char* dof : translations) builder.addChannel(joints[j].name + dof);
        }
        std::vector<double> values;
        for (unsigned f = 0; f < bench.numFrames; ++f)
            for (unsigned j = 0; j < joints.size(); ++j)
            {
                for (unsigned a = 0; a < 3; ++a) values.push_back(bench.anglesAt(f, j)[a]);
                if (j == 0)
                    for (unsigned a = 0; a < 3; ++a) values.push_back(bench.rootPosition[f * 3 + a]);
            }
        builder.setFrames(bench.framesPerSecond, std::move(values));
        return builder.build().clip;
    }();
    return clip;
}

} // namespace bench
