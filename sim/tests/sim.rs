use sitlog_sim::*;

fn home() -> World {
    World::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/worlds/home.toml"
    )))
    .unwrap_or_else(|e| panic!("{e:#?}"))
}

#[test]
fn scratch() {
    let w = home();
    let mut s = Sim::new(&w, 7);
    for o in w.object_names() {
        println!("{o}: {:?} {:?}", s.where_is(o), s.position(o));
    }
    println!("{:?}", s.navigate("shelf_food"));
    println!("{:?}", s.see());
    println!("{:?}", s.grasp("noodles", Hand::Left));
    println!("{:?}", s.navigate("kitchen_drinks"));
    println!("{:?}", s.see());
    println!("{:?}", s.place(Hand::Left));
    println!("{:?}", s.see());
    println!("{:?}", s.navigate("kitchen"));
    println!("{:?}", s.place(Hand::Left));
    println!("{:?}", s.grasp("malz", Hand::Left));
    for e in s.events() {
        println!("{:7.1} {e}   {:?}", e.time, e.kind);
    }
}
