//! Profiling aid: parse a 9,000-frame take built from 01_01.bvh once, with our
//! parser (`ours`), or the bare split+parse floor (`floor`).
fn main() {
    let mode = std::env::args().nth(1).unwrap_or_default();
    let src = std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/corpus/bvh/assimp_cmu/01_01.bvh"))
        .expect("corpus");
    let text = String::from_utf8(src).expect("utf8");
    let at = text.find("Frame Time").expect("ft");
    let rows_at = at + text[at..].find('\n').expect("nl") + 1;
    let rows: Vec<&str> = text[rows_at..].lines().collect();
    let mut input = text.as_bytes()[..rows_at].to_vec();
    for i in 0..9000 {
        input.extend_from_slice(rows[i % rows.len()].as_bytes());
        input.push(b'\n');
    }
    let t = std::time::Instant::now();
    let n = if mode == "floor" {
        let mut out = Vec::with_capacity(input.len() / 4);
        for tok in input[rows_at..].split(|b| b.is_ascii_whitespace()).filter(|t| !t.is_empty()) {
            if let Ok(v) = fast_float2::parse::<f32, _>(tok) {
                out.push(v);
            }
        }
        out.len()
    } else {
        mocap::formats::bvh::parse(&input).expect("parse").motion().data().len()
    };
    eprintln!("{mode}: {n} values, {} bytes, {:?}", input.len(), t.elapsed());
}
