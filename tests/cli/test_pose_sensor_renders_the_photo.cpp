// The two camera conventions meet here: the <sensor> that `surfscatter pose` writes (photo module, OpenCV's camera)
// must make the renderer (render module, Mitsuba's perspective sensor) put every world point on the pixel where the
// calibrated camera sees it. Checked without rendering, through render::Camera::project, with an off-centre
// principal point, for several poses.
#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "../photo/synthetic.hpp"
#include "surfscatter/photo/pose.hpp"
#include "surfscatter/render/camera.hpp"
#include "surfscatter/render/xml_loader.hpp"

namespace surfscatter {
namespace {

TEST(PoseSensor, TheRendererProjectsWorldPointsWhereTheCalibratedCameraSeesThem) {
    photo::CameraModel camera;
    camera.image_size = {1200, 900};
    camera.matrix = cv::Matx33d(1300.0, 0.0, 611.3, 0.0, 1300.0, 441.7, 0.0, 0.0, 1.0);
    camera.distortion.assign(5, 0.0);  // the sensor reproduces the undistorted photograph

    const std::vector<cv::Point3d> points{{0, 0, 0}, {0.1, 0.05, 0}, {-0.2, 0.1, 0.03}, {0.05, -0.15, 0.1}};
    for (const auto& [eye, up] : std::vector<std::pair<cv::Vec3d, cv::Vec3d>>{
             {{0.1, -0.5, 0.6}, {0, 0, 1}}, {{-0.4, 0.2, 0.5}, {0, 1, 0}}, {{0.3, 0.3, 0.2}, {1, -1, 0.5}}}) {
        const auto pose = photo::synthetic::look_at(eye, {0.0, 0.0, 0.0}, up);
        const photo::MitsubaSensor sensor = photo::mitsuba_sensor(camera, photo::synthetic::camera_to_world(pose), 0.7);

        // The sensor exactly as a user pastes it into a scene.
        const auto scene = render::load_scene_from_string("<scene version=\"3.0.0\">\n" + sensor.xml + "</scene>\n",
                                                          "pose_sensor.xml");
        ASSERT_EQ(scene->film.width, 1200);
        ASSERT_EQ(scene->film.height, 900);
        const render::Camera rendered(scene->camera, scene->film.width, scene->film.height);

        std::vector<cv::Point2d> seen;
        cv::projectPoints(points, pose.rvec, pose.tvec, camera.matrix, camera.distortion, seen);
        for (std::size_t k = 0; k < points.size(); ++k) {
            const auto film = rendered.project({points[k].x, points[k].y, points[k].z});
            ASSERT_TRUE(film.has_value());
            // Film positions count from the top-left corner of the image, OpenCV pixels from the first pixel's centre.
            EXPECT_NEAR(film->x - 0.5, seen[k].x, 1e-6) << "eye " << eye << ", point " << k;
            EXPECT_NEAR(film->y - 0.5, seen[k].y, 1e-6) << "eye " << eye << ", point " << k;
        }
    }
}

}  // namespace
}  // namespace surfscatter
