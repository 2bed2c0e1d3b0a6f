use super::*;
use crate::error::CovmapError;

fn parse(text: &str) -> Result<Log> {
    Log::read_carmen(
        std::io::Cursor::new(text.as_bytes().to_vec()),
        "t.log",
        &CarmenOptions::default(),
    )
}

fn parse_error(text: &str) -> (usize, String) {
    match parse(text) {
        Err(CovmapError::Parse { file, line, reason }) => {
            assert_eq!(file, "t.log");
            (line, reason)
        }
        other => panic!("expected a parse error, got {other:?}"),
    }
}

#[test]
fn flaser_lines_give_their_pose_ranges_time_and_fan() {
    let text = "# comment\nPARAM robot_frontlaser_offset 0.2 nohost 0\n\
                ODOM 0 0 0 0 0 0 1.0 h 1.0\n\
                FLASER 4 1.0 2.0 81.9 3.5 1.5 2.5 0.5 9 9 9 2.0 h 2.0\n\
                NEFF 1 2 3\n\
                FLASER 4 1.1 2.1 81.9 3.6 1.6 2.6 0.6 9 9 9 2.5 h 2.5\n";
    let log = parse(text).unwrap();
    assert_eq!((log.len(), log.beams()), (2, 4));
    assert_eq!(log.poses()[1], Pose::new(1.6, 2.6, 0.6));
    assert_eq!(log.timestamps_s(), &[2.0, 2.5]);
    assert_eq!(log.scan_ranges(0), &[1.0, 2.0, 81.9, 3.5]);
    assert_eq!(log.max_range_m(), 81.9);
    // FLASER poses are the laser's: the offset is not applied again.
    assert_eq!(log.sensor_offset(), Pose::default());
    let Bearings::Fixed(b) = log.bearings() else {
        panic!("one fan for every scan")
    };
    let step = std::f64::consts::PI / 4.0;
    for (k, v) in b.iter().enumerate() {
        assert!((v - (-std::f64::consts::FRAC_PI_2 + k as f64 * step)).abs() < 1e-15);
    }
}

#[test]
fn flaser_step_covers_180_degrees_by_its_parity() {
    let deg = |n| flaser_step_rad(n).to_degrees();
    assert!((deg(180) - 1.0).abs() < 1e-12 && (deg(181) - 1.0).abs() < 1e-12);
    assert!((deg(360) - 0.5).abs() < 1e-12 && (deg(361) - 0.5).abs() < 1e-12);
}

#[test]
fn rawlaser_takes_interpolated_odometry_and_the_offset() {
    let text = "PARAM robot_frontlaser_offset 0.25 h 0\n\
                PARAM robot_front_laser_max 8.0 h 0\n\
                ODOM 0 0 3.0 0 0 0 10.0 h 10\n\
                ODOM 2 4 -3.0 0 0 0 12.0 h 12\n\
                RAWLASER1 0 -1.0 2.0 0.5 20.0 0.01 0 3 1 2 3 2 7 7 11.0 h 11\n\
                RAWLASER1 0 -1.0 2.0 0.5 20.0 0.01 0 3 1 2 3 0 13.0 h 13\n";
    let log = parse(text).unwrap();
    let p = log.poses()[0];
    assert!((p.x_m - 1.0).abs() < 1e-12 && (p.y_m - 2.0).abs() < 1e-12);
    // From 3.0 to -3.0 the short way, through pi.
    let expected = 3.0 + 0.5 * (std::f64::consts::TAU - 6.0);
    assert!((p.theta_rad - expected).abs() < 1e-12, "{}", p.theta_rad);
    assert_eq!(log.poses()[1], Pose::new(2.0, 4.0, -3.0)); // after the last: the last
    // ODOM out of the file's order is taken in the order of time.
    let swapped = text.replace(
        "ODOM 0 0 3.0 0 0 0 10.0 h 10\nODOM 2 4 -3.0 0 0 0 12.0 h 12",
        "ODOM 2 4 -3.0 0 0 0 12.0 h 12\nODOM 0 0 3.0 0 0 0 10.0 h 10",
    );
    assert_ne!(swapped, text);
    assert_eq!(parse(&swapped).unwrap(), log);
    assert_eq!(log.sensor_offset(), Pose::new(0.25, 0.0, 0.0));
    assert_eq!(log.max_range_m(), 8.0); // the PARAM before the message's 20
    assert_eq!(log.scan_bearings(1), &[-1.0, -0.5, 0.0]);
}

#[test]
fn robotlaser_takes_the_laser_pose_and_per_scan_fans() {
    let text = "ROBOTLASER1 0 -1.0 2.0 0.5 20.0 0.01 0 2 1 2 0 1 2 0.1 9 9 9 0 0 0 0 0 5.0 h 5\n\
                ROBOTLASER1 0 -0.5 2.0 0.25 30.0 0.01 0 2 3 4 0 1 3 0.2 9 9 9 0 0 0 0 0 6.0 h 6\n\
                FLASER 2 1 1 0 0 0 0 0 0 7.0 h 7\n";
    let log = parse(text).unwrap();
    assert_eq!(log.len(), 2); // the FLASER is another kind: skipped
    assert_eq!(log.poses()[1], Pose::new(1.0, 3.0, 0.2));
    assert_eq!(log.max_range_m(), 30.0);
    assert!(matches!(log.bearings(), Bearings::PerScan(_)));
    assert_eq!(log.scan_bearings(1), &[-0.5, -0.25]);
}

#[test]
fn bad_lines_are_errors_naming_their_line() {
    let good = "FLASER 2 1 2 0 0 0 0 0 0 1.0 h 1\n";
    let cases = [
        ("FLASER 2 1 -2 0 0 0 0 0 0 1.0 h 1\n", "negative"),
        (
            "FLASER 2 1 nan 0 0 0 0 0 0 1.0 h 1\n",
            "not a finite number",
        ),
        ("FLASER 2 1 2 0 0 0\n", "ends before"),
        (
            "FLASER 3 1 2 3 0 0 0 0 0 0 1.0 h 1\n",
            "earlier scans have 2",
        ),
        ("FLASER 99999999999 1\n", "count from 0"),
        ("ODOM 0 0 x 0 0 0 1 h 1\n", "theta"),
    ];
    for (bad, says) in cases {
        let (line, reason) = parse_error(&format!("{good}{good}{bad}{good}"));
        assert_eq!(line, 3, "{bad}");
        assert!(reason.contains(says), "{bad}: {reason}");
    }
    let (line, reason) = parse_error("PARAM a b\nODOM 0 0 0 0 0 0 1 h 1\n");
    assert_eq!(line, 3);
    assert!(reason.contains("no FLASER"), "{reason}");
    let (line, _) = parse_error("RAWLASER1 0 -1 2 0.5 20 0.01 0 1 1 0 5.0 h 5\n");
    assert_eq!(line, 1, "a raw scan without odometry");
}

#[test]
fn bad_options_are_parameter_errors() {
    let options = CarmenOptions {
        max_range_m: Some(-1.0),
        ..Default::default()
    };
    let text = b"FLASER 1 1 0 0 0 0 0 0 1.0 h 1\n".to_vec();
    let err = Log::read_carmen(std::io::Cursor::new(text), "t", &options).unwrap_err();
    assert!(
        matches!(
            err,
            CovmapError::InvalidParameter {
                name: "max_range_m",
                ..
            }
        ),
        "{err}"
    );
}

fn parse_laser(text: &str, laser: CarmenLaser) -> Result<Log> {
    let options = CarmenOptions {
        laser,
        ..Default::default()
    };
    Log::read_carmen(
        std::io::Cursor::new(text.as_bytes().to_vec()),
        "t.log",
        &options,
    )
}

#[test]
fn rlaser_lines_are_the_rear_laser_log_and_never_mixed_into_the_front_one() {
    // A robot at (1, 2) heading 0.5: the front laser 0.2 m ahead, the rear
    // one 0.3 m behind and turned round; each line's pose is its laser's.
    let text = "PARAM robot_frontlaser_offset 0.2 h 0\n\
                PARAM robot_rearlaser_offset -0.3 h 0\n\
                PARAM robot_rear_laser_max 7.5 h 0\n\
                FLASER 3 1.0 2.0 3.0 1.2 2.0 0.5 1 2 0.5 4.0 h 4.0\n\
                RLASER 2 4.0 5.0 0.7 2.0 3.6 1 2 0.5 4.1 h 4.1\n\
                FLASER 3 1.5 2.5 3.5 1.3 2.0 0.5 1 2 0.5 5.0 h 5.0\n\
                RLASER 2 4.5 5.5 0.8 2.0 3.7 1 2 0.5 5.1 h 5.1\n";
    let front = parse_laser(text, CarmenLaser::Front).unwrap();
    assert_eq!((front.len(), front.beams()), (2, 3));
    assert_eq!(front.timestamps_s(), &[4.0, 5.0]);
    let rear = parse_laser(text, CarmenLaser::Rear).unwrap();
    assert_eq!((rear.len(), rear.beams()), (2, 2));
    assert_eq!(rear.timestamps_s(), &[4.1, 5.1]);
    assert_eq!(rear.poses()[1], Pose::new(0.8, 2.0, 3.7));
    assert_eq!(rear.scan_ranges(0), &[4.0, 5.0]);
    assert_eq!(rear.max_range_m(), 7.5);
    // As FLASER's, the pose is the laser's own: no offset applied again.
    assert_eq!(rear.sensor_offset(), Pose::default());
    // A log without rear messages names what it looked for.
    let only_front = "FLASER 1 1 0 0 0 0 0 0 1.0 h 1\n";
    match parse_laser(only_front, CarmenLaser::Rear) {
        Err(CovmapError::Parse { reason, .. }) => {
            assert!(
                reason.contains("no RLASER, ROBOTLASER2 or RAWLASER2"),
                "{reason}"
            )
        }
        other => panic!("expected a parse error, got {other:?}"),
    }
}

#[test]
fn rawlaser2_takes_the_rear_lasers_mounting() {
    let text = "PARAM robot_frontlaser_offset 0.25 h 0\n\
                PARAM robot_rearlaser_offset -0.3 h 0\n\
                PARAM robot_rearlaser_side_offset 0.05 h 0\n\
                PARAM robot_rearlaser_angular_offset 3.0 h 0\n\
                ODOM 0 0 0 0 0 0 10.0 h 10\n\
                RAWLASER1 0 -1.0 2.0 0.5 20.0 0.01 0 3 1 2 3 0 10.0 h 10\n\
                RAWLASER2 0 -1.0 2.0 1.0 9.0 0.01 0 2 4 5 0 10.0 h 10\n";
    let rear = parse_laser(text, CarmenLaser::Rear).unwrap();
    assert_eq!((rear.len(), rear.beams(), rear.max_range_m()), (1, 2, 9.0));
    assert_eq!(rear.sensor_offset(), Pose::new(-0.3, 0.05, 3.0));
    let front = parse_laser(text, CarmenLaser::Front).unwrap();
    assert_eq!(
        (front.beams(), front.sensor_offset()),
        (3, Pose::new(0.25, 0.0, 0.0))
    );
}
