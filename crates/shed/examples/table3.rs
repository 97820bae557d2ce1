//! Prints the reproduction of the paper's Table 3: `cargo run -p loomkin-shed --example table3`.

fn main() -> Result<(), loomkin_shed::ShedError> {
    let (t, worst) = loomkin_shed::table3_minimax_threshold()?;
    println!("minimax threshold T = {t:.4} (largest deviation {worst:.2} deg)");
    for threshold in [0.85, 0.95, t] {
        println!("\nT = {threshold:.4}");
        println!(
            "law          dwell_deg  cond_paper_deg  cond_ours_deg  window_paper_deg  window_ours_deg  row_T  ca     a_m_s2"
        );
        for r in loomkin_shed::table3(threshold)? {
            println!(
                "{:<12} {:>9.0} {:>15.0} {:>14.2} {:>17.0} {:>16.2} {:>6.4} {:>6.3} {:>7.2}",
                r.paper.name,
                r.ours.dwell_deg,
                r.paper.conditional_dwell_deg,
                r.ours.conditional_dwell_deg,
                r.paper.window_deg,
                r.ours.window_deg,
                r.row_threshold,
                r.ours.ca,
                r.ours.peak_accel_m_s2
            );
        }
    }
    Ok(())
}
