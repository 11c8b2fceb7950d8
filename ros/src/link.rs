//! The DDS side of a node: one participant on the domain `ROS_DOMAIN_ID`
//! (loopback only when `ROS_LOCALHOST_ONLY=1` or
//! `ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST`), a ros2-client node with its
//! spinner on a thread of its own, the typed endpoints of the interface,
//! and waits with a deadline ([`wait_for`]).
//!
//! Invariant: nothing here waits without a deadline or without looking at
//! the caller's stop flag at least every [`TICK`].

use crate::config::Qos;
use futures::future::{self, Either};
use ros2_client::dds::rustdds;
use ros2_client::qos::{Durability, History, Reliability, WhenFull};
use ros2_client::{
    ActionTypeName, Context, MessageTypeName, Name, Node, NodeName, NodeOptions, QosProfile,
    ServiceTypeName,
};
use serde::Serialize;
use std::future::Future;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// How often a wait looks at its stop flag.
pub const TICK: Duration = Duration::from_millis(100);

/// The DDS domain of this process: `ROS_DOMAIN_ID` (0 to 232), else 0.
pub fn domain_id() -> Result<u16, String> {
    match std::env::var("ROS_DOMAIN_ID") {
        Ok(v) if !v.trim().is_empty() => v
            .trim()
            .parse::<u16>()
            .ok()
            .filter(|d| *d <= 232)
            .ok_or_else(|| format!("error: ROS_DOMAIN_ID=`{v}` is not a domain id (0 to 232)")),
        _ => Ok(0),
    }
}

/// Whether discovery and traffic stay on this host (ROS 2's variables).
pub fn localhost_only() -> bool {
    let var = |k: &str| std::env::var(k).unwrap_or_default();
    var("ROS_LOCALHOST_ONLY") == "1"
        || var("ROS_AUTOMATIC_DISCOVERY_RANGE").eq_ignore_ascii_case("localhost")
}

/// A node on the domain, its spinner running.
pub struct Link {
    pub context: Context,
    pub node: Node,
    pub node_name: NodeName,
    pub domain: u16,
    publisher: rustdds::Publisher,
}

fn err(what: &str, e: impl std::fmt::Display) -> String {
    format!("error: ROS 2: {what}: {e}")
}

impl Link {
    /// Joins the domain of the environment ([`domain_id`],
    /// [`localhost_only`]) as node `/sitlog/NAME`.
    pub fn open(name: &str) -> Result<Link, String> {
        Link::open_on(name, domain_id()?, localhost_only())
    }

    /// Joins `domain` as node `/sitlog/NAME`, on loopback only with `local`.
    pub fn open_on(name: &str, domain: u16, local: bool) -> Result<Link, String> {
        let mut builder = rustdds::DomainParticipantBuilder::new(domain);
        if local {
            builder = builder.with_only_networks([std::net::Ipv4Addr::LOCALHOST]);
        }
        let participant = builder
            .build()
            .map_err(|e| err(&format!("cannot join DDS domain {domain}"), e))?;
        let context = Context::from_domain_participant(participant)
            .map_err(|e| err("cannot make a context", e))?;
        let node_name = NodeName::new("/sitlog", name).map_err(|e| err("node name", e))?;
        let mut node = context
            .new_node(
                node_name.clone(),
                NodeOptions::new()
                    .enable_rosout(false)
                    .start_parameter_services(false),
            )
            .map_err(|e| err("cannot make the node", e))?;
        let spinner = node.spinner().map_err(|e| err("node spinner", e))?;
        std::thread::Builder::new()
            .name("sitlog-ros-spin".into())
            .spawn(move || {
                let _ = futures::executor::block_on(spinner.spin());
            })
            .map_err(|e| err("spinner thread", e))?;
        let publisher = context
            .domain_participant()
            .create_publisher(&rustdds::QosPolicyBuilder::new().build())
            .map_err(|e| err("DDS publisher", e))?;
        Ok(Link {
            context,
            node,
            node_name,
            domain,
            publisher,
        })
    }

    fn topic(
        &self,
        name: &str,
        ty: (&str, &str),
        qos: &QosProfile,
    ) -> Result<rustdds::Topic, String> {
        let ros = Name::parse(name).map_err(|e| err(&format!("topic name `{name}`"), e))?;
        self.context
            .create_topic(
                ros.to_dds_name("rt", &self.node_name, ""),
                MessageTypeName::new(ty.0, ty.1),
                qos,
            )
            .map_err(|e| err(&format!("topic {name}"), e))
    }

    /// A writer on topic `name` of type `ty` (package, name) whose
    /// messages can be waited on until every reader has them.
    pub fn writer<M: Serialize>(
        &self,
        name: &str,
        ty: (&str, &str),
        qos: &Qos,
    ) -> Result<Writer<M>, String> {
        let profile = profile(qos);
        let topic = self.topic(name, ty, &profile)?;
        let writer = self
            .publisher
            .create_datawriter_no_key_cdr::<M>(&topic, Some(rustdds::QosPolicies::from(&profile)))
            .map_err(|e| err(&format!("writer on {name}"), e))?;
        Ok(Writer {
            writer,
            name: name.to_owned(),
            matched: Default::default(),
        })
    }

    /// A subscription on topic `name` of type `ty`.
    pub fn subscription<M: 'static + serde::de::DeserializeOwned>(
        &mut self,
        name: &str,
        ty: (&str, &str),
        qos: &Qos,
    ) -> Result<ros2_client::Subscription<M>, String> {
        let profile = profile(qos);
        let topic = self.topic(name, ty, &profile)?;
        self.node
            .create_subscription::<M>(&topic, Some(profile))
            .map_err(|e| err(&format!("subscription to {name}"), e))
    }

    /// An action client for `name` of type `ty` (package, action).
    pub fn action_client<G, R, F>(
        &mut self,
        name: &str,
        ty: (&str, &str),
    ) -> Result<ros2_client::ActionClient<G, R, F>, String>
    where
        G: ros2_client::Message + Clone + 'static,
        R: ros2_client::Message + Clone + 'static,
        F: ros2_client::Message + 'static,
    {
        let ros = Name::parse(name).map_err(|e| err(&format!("action name `{name}`"), e))?;
        let q = service_qos();
        self.node
            .create_action_client::<G, R, F>(
                ros2_client::ServiceMapping::Enhanced,
                &ros,
                &ActionTypeName::new(ty.0, ty.1),
                ros2_client::action::ActionClientQosPolicies {
                    goal_service: q.clone(),
                    result_service: q.clone(),
                    cancel_service: q.clone(),
                    feedback_subscription: q.clone(),
                    status_subscription: q,
                },
            )
            .map_err(|e| err(&format!("action client {name}"), e))
    }

    /// An action server for `name` of type `ty`.
    pub fn action_server<G, R, F>(
        &mut self,
        name: &str,
        ty: (&str, &str),
    ) -> Result<ros2_client::ActionServer<G, R, F>, String>
    where
        G: ros2_client::Message + Clone + 'static,
        R: ros2_client::Message + Clone + 'static,
        F: ros2_client::Message + 'static,
    {
        let ros = Name::parse(name).map_err(|e| err(&format!("action name `{name}`"), e))?;
        let q = service_qos();
        self.node
            .create_action_server::<G, R, F>(
                ros2_client::ServiceMapping::Enhanced,
                &ros,
                &ActionTypeName::new(ty.0, ty.1),
                ros2_client::action::ActionServerQosPolicies {
                    goal_service: q.clone(),
                    result_service: q.clone(),
                    cancel_service: q.clone(),
                    feedback_publisher: q.clone(),
                    status_publisher: q,
                },
            )
            .map_err(|e| err(&format!("action server {name}"), e))
    }

    /// A service client for `name` of type `ty` (package, service).
    pub fn client<Q, A>(
        &mut self,
        name: &str,
        ty: (&str, &str),
    ) -> Result<ros2_client::Client<Q, A>, String>
    where
        Q: ros2_client::Message + Clone + 'static,
        A: ros2_client::Message + 'static,
    {
        let ros = Name::parse(name).map_err(|e| err(&format!("service name `{name}`"), e))?;
        self.node
            .create_client::<Q, A>(
                ros2_client::ServiceMapping::Enhanced,
                &ros,
                &ServiceTypeName::new(ty.0, ty.1),
                service_qos(),
                service_qos(),
            )
            .map_err(|e| err(&format!("service client {name}"), e))
    }

    /// A service server for `name` of type `ty`.
    pub fn server<Q, A>(
        &mut self,
        name: &str,
        ty: (&str, &str),
    ) -> Result<ros2_client::Server<Q, A>, String>
    where
        Q: ros2_client::Message + Clone + 'static,
        A: ros2_client::Message + 'static,
    {
        let ros = Name::parse(name).map_err(|e| err(&format!("service name `{name}`"), e))?;
        self.node
            .create_server::<Q, A>(
                ros2_client::ServiceMapping::Enhanced,
                &ros,
                &ServiceTypeName::new(ty.0, ty.1),
                service_qos(),
                service_qos(),
            )
            .map_err(|e| err(&format!("service server {name}"), e))
    }

    /// How many readers of other participants the domain has on topic
    /// `name` (a ROS name, `rt/` topics).
    pub fn remote_readers(&self, name: &str) -> usize {
        let dds = format!("rt{name}");
        let me = rustdds::RTPSEntity::guid(&self.context.domain_participant()).prefix;
        self.context
            .domain_participant()
            .discovered_readers()
            .iter()
            .filter(|r| r.subscription_topic_data.topic_name() == &dds)
            .filter(|r| r.reader_proxy.remote_reader_guid.prefix != me)
            .count()
    }

    /// Whether another participant serves the service `name` (a ROS name:
    /// it reads the `rq/...Request` topic), as far as discovery knows.
    pub fn remote_server(&self, name: &str) -> bool {
        let dds = format!("rq{name}Request");
        let me = rustdds::RTPSEntity::guid(&self.context.domain_participant()).prefix;
        self.context
            .domain_participant()
            .discovered_readers()
            .iter()
            .any(|r| {
                r.subscription_topic_data.topic_name() == &dds
                    && r.reader_proxy.remote_reader_guid.prefix != me
            })
    }

    /// How many readers of other participants on topic `name` are
    /// reliable (they acknowledge what they get: a robot, not a console
    /// that only watches).
    pub fn remote_reliable_readers(&self, name: &str) -> usize {
        let dds = format!("rt{name}");
        let me = rustdds::RTPSEntity::guid(&self.context.domain_participant()).prefix;
        self.context
            .domain_participant()
            .discovered_readers()
            .iter()
            .filter(|r| r.subscription_topic_data.topic_name() == &dds)
            .filter(|r| r.reader_proxy.remote_reader_guid.prefix != me)
            .filter(|r| {
                matches!(
                    r.subscription_topic_data.qos().reliability(),
                    Some(rustdds::policy::Reliability::Reliable { .. })
                )
            })
            .count()
    }

    /// The writers of other participants on topic `name`: how many
    /// publish `type_name` (a DDS type name, `std_msgs::msg::dds_::Bool_`),
    /// and the types of the others (a foreign node's, issue 38).
    pub fn remote_writers(&self, name: &str, type_name: &str) -> (usize, Vec<String>) {
        let dds = format!("rt{name}");
        let me = rustdds::RTPSEntity::guid(&self.context.domain_participant()).prefix;
        let mut same = 0;
        let mut foreign = Vec::new();
        for w in self.context.domain_participant().discovered_writers() {
            let data = &w.publication_topic_data;
            if data.topic_name != dds || w.writer_proxy.remote_writer_guid.prefix == me {
                continue;
            }
            if data.type_name == type_name {
                same += 1;
            } else {
                foreign.push(data.type_name.clone());
            }
        }
        (same, foreign)
    }
}

/// Services and actions: reliable, volatile, keep last 10 (ROS 2's
/// services default).
fn service_qos() -> QosProfile {
    QosProfile::publisher_default().history(History::KeepLast { depth: 10 })
}

/// The ros2-client profile of a `[qos.TOPIC]`.
pub fn profile(q: &Qos) -> QosProfile {
    let reliability = if q.reliability == "best_effort" {
        Reliability::BestEffort
    } else {
        Reliability::Reliable {
            when_full: WhenFull::DEFAULT,
        }
    };
    let durability = if q.durability == "transient_local" {
        Durability::TransientLocal
    } else {
        Durability::Volatile
    };
    QosProfile::subscription_default()
        .reliability(reliability)
        .durability(durability)
        .history(History::KeepLast {
            depth: q.depth.max(1) as usize,
        })
}

/// A writer whose messages can be waited on ([`Writer::send`]).
pub struct Writer<M: Serialize> {
    writer: rustdds::no_key::DataWriterCdr<M>,
    pub name: String,
    /// Readers matched, as the last status event said.
    matched: std::sync::atomic::AtomicUsize,
}

impl<M: Serialize> Writer<M> {
    /// Publishes `message`; with `ack`, waits at most that long until
    /// every matched reader has it. `Ok(false)`: a reader did not
    /// acknowledge it in time.
    pub fn send(&self, message: M, ack: Option<Duration>) -> Result<bool, String> {
        self.writer
            .write(message, Some(rustdds::Timestamp::now()))
            .map_err(|e| format!("cannot publish on {}: {e}", self.name))?;
        match ack {
            None => Ok(true),
            Some(d) => self
                .writer
                .wait_for_acknowledgments(d)
                .map_err(|e| format!("publishing on {}: {e}", self.name)),
        }
    }

    /// How many readers this writer has matched (a reader discovery has
    /// announced may not be matched yet), from its status events.
    pub fn matched(&self) -> usize {
        use rustdds::StatusEvented;
        while let Some(status) = self.writer.try_recv_status() {
            if let rustdds::DataWriterStatus::PublicationMatched { current, .. } = status {
                let n = usize::try_from(current.count()).unwrap_or(0);
                self.matched.store(n, Ordering::SeqCst);
            }
        }
        self.matched.load(Ordering::SeqCst)
    }

    /// Waits (at most `limit`, looking at `stop` every [`TICK`]) until this
    /// writer has matched every reader discovery knows on its topic, so
    /// that a volatile message reaches them all. `false`: it has not.
    pub fn wait_matched(&self, link: &Link, limit: Duration, stop: &AtomicBool) -> bool {
        let start = Instant::now();
        loop {
            let known = link.remote_readers(&self.name);
            if known > 0 && self.matched() >= known {
                return true;
            }
            if start.elapsed() >= limit || stop.load(Ordering::SeqCst) {
                return false;
            }
            std::thread::sleep(Duration::from_millis(10).min(TICK));
        }
    }
}

/// How a wait ended.
pub enum Waited<T> {
    Done(T),
    TimedOut,
    Stopped,
}

/// Runs `f` to its end, at most `limit` (`None`: no limit), looking at
/// `stop` every [`TICK`].
pub fn wait_for<F: Future>(f: F, limit: Option<Duration>, stop: &AtomicBool) -> Waited<F::Output> {
    let start = Instant::now();
    let mut f = Box::pin(f);
    loop {
        if stop.load(Ordering::SeqCst) {
            return Waited::Stopped;
        }
        let mut tick = TICK;
        if let Some(limit) = limit {
            let left = limit.saturating_sub(start.elapsed());
            if left.is_zero() {
                return Waited::TimedOut;
            }
            tick = tick.min(left);
        }
        let timer = Timer::after(tick);
        match futures::executor::block_on(future::select(f, timer)) {
            Either::Left((out, _)) => return Waited::Done(out),
            Either::Right(((), rest)) => f = rest,
        }
    }
}

/// A future that ends after a while (a thread that sleeps, and ends early
/// when the future is dropped).
struct Timer {
    rx: futures::channel::oneshot::Receiver<()>,
    _cancel: std::sync::mpsc::Sender<()>,
}

impl Timer {
    fn after(d: Duration) -> Timer {
        let (tx, rx) = futures::channel::oneshot::channel();
        let (cancel, cancelled) = std::sync::mpsc::channel::<()>();
        let _ = std::thread::Builder::new()
            .name("sitlog-ros-timer".into())
            .spawn(move || {
                if let Err(std::sync::mpsc::RecvTimeoutError::Timeout) = cancelled.recv_timeout(d) {
                    let _ = tx.send(());
                }
            });
        Timer {
            rx,
            _cancel: cancel,
        }
    }
}

impl Future for Timer {
    type Output = ();
    fn poll(
        mut self: std::pin::Pin<&mut Self>,
        cx: &mut std::task::Context<'_>,
    ) -> std::task::Poll<()> {
        match std::pin::Pin::new(&mut self.rx).poll(cx) {
            std::task::Poll::Ready(_) => std::task::Poll::Ready(()),
            std::task::Poll::Pending => std::task::Poll::Pending,
        }
    }
}
