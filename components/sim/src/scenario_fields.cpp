#include "scenario_fields.hpp"

namespace uavmot::sim::detail {

void visit_scenario(Scenario& s, FieldVisitor& v) {
  v.field("name", s.name);
  v.field("frames", s.frames, 1, 100000);
  v.field("fps", s.fps, 0.1, 1000.0);

  CameraParams& c = s.camera;
  v.begin_section("camera");
  v.field("width", c.width, 32, 8192);
  v.field("height", c.height, 32, 8192);
  v.field("gsd_m", c.gsd_m, 0.01, 10.0);
  v.field("altitude_m", c.altitude_m, 5.0, 20000.0);
  v.field("speed_mps", c.speed_mps, 0.0, 1000.0);
  v.field("heading_deg", c.heading_deg, -360.0, 360.0);
  v.field("path_curvature_dps", c.path_curvature_dps, -90.0, 90.0);
  v.field("yaw_deg", c.yaw_deg, -360.0, 360.0);
  v.field("yaw_rate_dps", c.yaw_rate_dps, -90.0, 90.0);
  v.field("yaw_wobble_deg", c.yaw_wobble_deg, 0.0, 45.0);
  v.field("altitude_change", c.altitude_change, 0.0, 0.5);
  v.field("altitude_period_s", c.altitude_period_s, 0.5, 10000.0);
  v.field("tilt_deg", c.tilt_deg, 0.0, 15.0);
  v.field("wobble_period_s", c.wobble_period_s, 0.5, 10000.0);
  v.field("pitch_deg", c.pitch_deg, -45.0, 45.0);
  v.end_section();

  GroundParams& g = s.ground;
  v.begin_section("ground");
  v.field("texture_dir", g.texture_dir);
  v.field("texture_gsd_m", g.texture_gsd_m, 0.01, 20.0);
  v.field("texture_contrast", g.texture_contrast, 0.0, 5.0);
  v.field("detail_noise", g.detail_noise, 0.0, 50.0);
  v.field("raster_max_megapixels", g.raster_max_megapixels, 1, 2000);
  v.end_section();

  RoadParams& r = s.roads;
  v.begin_section("roads");
  v.field("main_road_angle_deg", r.main_road_angle_deg, -180.0, 180.0);
  v.field("main_lanes_per_direction", r.main_lanes_per_direction, 1, 4);
  v.field("cross_roads", r.cross_roads, 0, 6);
  v.field("curved_roads", r.curved_roads, 0, 4);
  v.field("side_lanes_per_direction", r.side_lanes_per_direction, 1, 3);
  v.field("lane_width_m", r.lane_width_m, 2.0, 6.0);
  v.field("asphalt_gray", r.asphalt_gray, 0.0, 255.0);
  v.field("asphalt_opacity", r.asphalt_opacity, 0.0, 1.0);
  v.field("marking_gray", r.marking_gray, 0.0, 255.0);
  v.field("marking_width_m", r.marking_width_m, 0.0, 1.0);
  v.field("dash_length_m", r.dash_length_m, 0.1, 100.0);
  v.field("dash_gap_m", r.dash_gap_m, 0.0, 100.0);
  v.end_section();

  TrafficParams& t = s.traffic;
  v.begin_section("traffic");
  v.field("flow_per_lane_vph", t.flow_per_lane_vph, 0.0, 5000.0);
  v.field("speed_min_mps", t.speed_min_mps, 0.0, 80.0);
  v.field("speed_max_mps", t.speed_max_mps, 0.0, 80.0);
  v.field("side_road_speed_factor", t.side_road_speed_factor, 0.05, 2.0);
  v.field("van_fraction", t.van_fraction, 0.0, 1.0);
  v.field("truck_fraction", t.truck_fraction, 0.0, 1.0);
  v.field("dark_fraction", t.dark_fraction, 0.0, 1.0);
  v.field("convoy_probability", t.convoy_probability, 0.0, 1.0);
  v.field("overtake_eagerness", t.overtake_eagerness, 0.0, 10.0);
  v.field("side_by_side_probability", t.side_by_side_probability, 0.0, 1.0);
  v.field("stop_period_s", t.stop_period_s, 1.0, 10000.0);
  v.field("stop_red_s", t.stop_red_s, 0.0, 10000.0);
  v.field("parked_vehicles", t.parked_vehicles, 0, 500);
  v.field("moving_threshold_mps", t.moving_threshold_mps, 0.0, 10.0);
  v.field("warmup_s", t.warmup_s, 0.0, 3600.0);
  v.field("shadow_length_m", t.shadow_length_m, 0.0, 10.0);
  v.field("shadow_angle_deg", t.shadow_angle_deg, -360.0, 360.0);
  v.field("shadow_strength", t.shadow_strength, 0.0, 1.0);
  v.field("vehicle_size_scale", t.vehicle_size_scale, 0.5, 2.0);
  v.end_section();

  StructureParams& b = s.structures;
  v.begin_section("structures");
  v.field("building_density_per_ha", b.building_density_per_ha, 0.0, 20.0);
  v.field("building_size_min_m", b.building_size_min_m, 3.0, 100.0);
  v.field("building_size_max_m", b.building_size_max_m, 3.0, 100.0);
  v.field("building_height_min_m", b.building_height_min_m, 1.0, 150.0);
  v.field("building_height_max_m", b.building_height_max_m, 1.0, 150.0);
  v.field("building_roadside_fraction", b.building_roadside_fraction, 0.0, 1.0);
  v.field("tree_density_per_ha", b.tree_density_per_ha, 0.0, 50.0);
  v.field("tree_radius_min_m", b.tree_radius_min_m, 0.5, 15.0);
  v.field("tree_radius_max_m", b.tree_radius_max_m, 0.5, 15.0);
  v.field("tree_height_min_m", b.tree_height_min_m, 2.0, 60.0);
  v.field("tree_height_max_m", b.tree_height_max_m, 2.0, 60.0);
  v.field("tree_roadside_fraction", b.tree_roadside_fraction, 0.0, 1.0);
  v.field("wall_density_per_ha", b.wall_density_per_ha, 0.0, 20.0);
  v.field("wall_length_min_m", b.wall_length_min_m, 2.0, 200.0);
  v.field("wall_length_max_m", b.wall_length_max_m, 2.0, 200.0);
  v.field("wall_height_min_m", b.wall_height_min_m, 0.5, 10.0);
  v.field("wall_height_max_m", b.wall_height_max_m, 0.5, 10.0);
  v.field("sun_azimuth_deg", b.sun_azimuth_deg, -360.0, 360.0);
  v.field("sun_elevation_deg", b.sun_elevation_deg, 5.0, 90.0);
  v.end_section();

  SensorParams& n = s.sensor;
  v.begin_section("sensor");
  v.field("blur_sigma_px", n.blur_sigma_px, 0.0, 10.0);
  v.field("noise_sigma", n.noise_sigma, 0.0, 100.0);
  v.field("gain_drift", n.gain_drift, 0.0, 0.9);
  v.field("gain_period_s", n.gain_period_s, 0.1, 10000.0);
  v.field("brightness_offset", n.brightness_offset, -255.0, 255.0);
  v.field("contrast", n.contrast, 0.0, 5.0);
  v.field("jpeg_quality", n.jpeg_quality, 1, 100);
  v.field("write_video", n.write_video);
  v.end_section();
}

}  // namespace uavmot::sim::detail
