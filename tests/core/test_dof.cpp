#include <osgActor/core/Dof>

#include <gtest/gtest.h>

using namespace osgActor;

TEST(Dof, UnknownNamesAreRefused)
{
    Dof dof = Dof::RX;
    EXPECT_FALSE(parseDof("", dof));
    EXPECT_FALSE(parseDof("rw", dof));
    EXPECT_FALSE(parseDof("rx ", dof));
    EulerOrder order = EulerOrder::XYZ;
    EXPECT_FALSE(parseEulerOrder("XXY", order));
    EXPECT_FALSE(parseEulerOrder("XY", order));
    EXPECT_EQ(order, EulerOrder::XYZ);
}

TEST(Dof, NamesRoundTrip)
{
    for (unsigned i = 0; i < kNumDofTypes; ++i)
    {
        Dof parsed = Dof::RX;
        ASSERT_TRUE(parseDof(dofName(static_cast<Dof>(i)), parsed));
        EXPECT_EQ(static_cast<unsigned>(parsed), i);
    }
    Dof upper = Dof::RX;
    ASSERT_TRUE(parseDof("TZ", upper));
    EXPECT_EQ(upper, Dof::TZ);
}

TEST(Dof, EulerOrderAxesAreTheLettersInProductOrder)
{
    EulerOrder order = EulerOrder::XYZ;
    ASSERT_TRUE(parseEulerOrder("zxy", order));
    EXPECT_EQ(order, EulerOrder::ZXY);
    EXPECT_STREQ(eulerOrderName(order), "ZXY");
    unsigned axes[3];
    eulerOrderAxes(order, axes);
    EXPECT_EQ(axes[0], 2u);
    EXPECT_EQ(axes[1], 0u);
    EXPECT_EQ(axes[2], 1u);
}

TEST(Dof, MasksAndAxes)
{
    EXPECT_EQ(kPaperDofs, 0x0F);
    EXPECT_EQ(Dof::RX | Dof::TZ, 0x21);
    EXPECT_TRUE(isRotation(Dof::RZ));
    EXPECT_FALSE(isRotation(Dof::TX));
    EXPECT_EQ(axisOf(Dof::TY), 1u);
}
