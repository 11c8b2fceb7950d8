//! Measures, over loopback, the latency of one `say` to a subscriber and of
//! one `heard` to the speech situation waiting for it (from the robot's
//! publish to `Perception::perceive` returning, which includes publishing
//! `false` on the listening topic and its acknowledgement), N times each;
//! prints the median, 90th percentile and maximum.
//!
//! `cargo run --release -p sitlog-ros --example latency` (domain 201,
//! loopback only; `ROS_DOMAIN_ID` to choose another).

use sitlog_robot::console::Console;
use sitlog_robot::interrupt::Interrupt;
use sitlog_ros::link::{wait_for, Link, Waited};
use sitlog_ros::msgs::{StdBool, StdString};
use sitlog_ros::{Interface, RosRobot};
use sitlog_runtime::{Atom, Store, Term};
use std::sync::atomic::AtomicBool;
use std::sync::mpsc;
use std::time::{Duration, Instant};

const N: usize = 200;

fn report(what: &str, mut times: Vec<Duration>) {
    times.sort();
    let at = |q: f64| times[((times.len() - 1) as f64 * q) as usize];
    println!(
        "{what}: median {:.0} µs, p90 {:.0} µs, max {:.0} µs ({} samples)",
        at(0.5).as_secs_f64() * 1e6,
        at(0.9).as_secs_f64() * 1e6,
        at(1.0).as_secs_f64() * 1e6,
        times.len()
    );
}

fn main() {
    let domain: u16 = std::env::var("ROS_DOMAIN_ID")
        .ok()
        .and_then(|d| d.parse().ok())
        .unwrap_or(201);
    let iface = Interface::load(None, None).unwrap();
    let q = iface.qos.clone();

    // The robot's side: hears `say` (one node), answers each listen on
    // `heard` (another).
    let (said_tx, said_rx) = mpsc::channel::<Instant>();
    let (asked_tx, asked_rx) = mpsc::channel::<Instant>();
    let voice_q = q.clone();
    std::thread::spawn(move || {
        let mut voice = Link::open_on("voice", domain, true).unwrap();
        let say = voice
            .subscription::<StdString>("/sitlog/say", ("std_msgs", "String"), &voice_q.say)
            .unwrap();
        let stop = AtomicBool::new(false);
        loop {
            if let Waited::Done(Ok(_)) = wait_for(say.async_take(), None, &stop) {
                let _ = said_tx.send(Instant::now());
            }
        }
    });
    let ears_q = q.clone();
    std::thread::spawn(move || {
        let mut ears = Link::open_on("ears", domain, true).unwrap();
        let listening = ears
            .subscription::<StdBool>("/sitlog/listening", ("std_msgs", "Bool"), &ears_q.listening)
            .unwrap();
        let heard = ears
            .writer::<StdString>("/sitlog/heard", ("std_msgs", "String"), &ears_q.heard)
            .unwrap();
        let stop = AtomicBool::new(false);
        loop {
            if let Waited::Done(Ok((m, _))) = wait_for(listening.async_take(), None, &stop) {
                if m.data {
                    let _ = asked_tx.send(Instant::now());
                    heard
                        .send(
                            StdString {
                                data: "hello".into(),
                            },
                            None,
                        )
                        .unwrap();
                }
            }
        }
    });

    // `say`: from the task's publish to the robot's subscriber.
    let task = Link::open_on("task_say", domain, true).unwrap();
    let say = task
        .writer::<StdString>("/sitlog/say", ("std_msgs", "String"), &q.say)
        .unwrap();
    std::thread::sleep(Duration::from_secs(2));
    let mut says = Vec::new();
    for i in 0..N {
        let t0 = Instant::now();
        say.send(
            StdString {
                data: format!("utterance {i}"),
            },
            None,
        )
        .unwrap();
        let t1 = said_rx.recv_timeout(Duration::from_secs(5)).expect("heard");
        says.push(t1 - t0);
        std::thread::sleep(Duration::from_millis(5));
    }
    drop(task);
    report("say → subscriber", says);

    // `heard`: from the robot's publish to the waiting speech situation.
    std::env::set_var("ROS_DOMAIN_ID", domain.to_string());
    std::env::set_var("ROS_LOCALHOST_ONLY", "1");
    let robot = RosRobot::connect(iface, Console::sink().shared(), Interrupt::new())
        .map_err(|e| e.1)
        .unwrap();
    let (mut senses, _effectors) = robot.split();
    let mut store = Store::new();
    let speech = Term::atom(Atom::intern("speech"));
    let mut heards = Vec::new();
    for _ in 0..N {
        match senses.perceive(&mut store, speech, &[]) {
            Ok(_) => {
                let t1 = Instant::now();
                let t0 = asked_rx
                    .recv_timeout(Duration::from_secs(5))
                    .expect("asked");
                heards.push(t1 - t0);
            }
            Err(e) => panic!("{e}"),
        }
    }
    report("heard → waiting situation", heards);
}
