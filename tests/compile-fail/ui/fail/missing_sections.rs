use mechgen::mechanism;

mechanism! {
    pub struct Empty {
        params: l1;
    }
}

fn main() {}
