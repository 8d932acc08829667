//! A problem file of a chain of bodies, as long as asked: the benchmarks time its export and
//! the tests read, study and export it (issue 50, cases 4 and 19).

/// A network of `n` bodies in a row 10 mm apart, each on a strip hinge from the end of the one
/// before (the first from the ground) and its face a fillet (0.5 mm) beyond the hinge, pushed
/// and read at the last; `extra` appended.
pub fn chain_problem(n: usize, extra: &str) -> String {
    let mut o = String::from(
        "model = \"network\"\nname = \"chain\"\n[material]\npreset = \"al7075-t6\"\n\
         [network]\nwidth = \"10 mm\"\nunit = \"mm\"\n\
         parameters = [[\"l\", \"length\"], [\"t\", \"length\"]]\n",
    );
    for i in 0..n {
        let x = 10 * i;
        o += &format!(
            "[[network.bodies]]\nname = \"b{i}\"\n\
             link = {{ from = [\"{x} + l + 0.5\", \"0\"], to = [\"{}\", \"0\"], width = \"3\" }}\n",
            x as f64 + 9.5
        );
    }
    for i in 0..n {
        let from = if i == 0 {
            "ground".to_string()
        } else {
            format!("b{}", i - 1)
        };
        o += &format!(
            "[[network.hinges]]\nname = \"h{i}\"\nkind = \"strip\"\nfrom = \"{from}\"\n\
             to = \"b{i}\"\nstart = [\"{}\", \"0\"]\nangle = \"0\"\nl = \"l\"\nt = \"t\"\n",
            10 * i
        );
    }
    let last = n - 1;
    o += &format!(
        "[network.input]\nbody = \"b{last}\"\nat = [\"{}\", \"0\"]\ndirection = [\"0\", \"1\"]\n\
         [[network.outputs]]\nname = \"tip\"\nbody = \"b{last}\"\nat = [\"{}\", \"0\"]\n\
         direction = [\"0\", \"1\"]\n\
         [actuator]\nnominal_stroke = \"0.01 um\"\npreload = \"0.01 N\"\n\
         [[variables]]\nname = \"l\"\nunit = \"mm\"\nlower = 1.5\nupper = 2\n\
         [[variables]]\nname = \"t\"\nunit = \"mm\"\nlower = 0.3\nupper = 0.6\n\
         [objective]\nmaximize = \"k_in\"\n\
         [[constraints]]\noutput = \"stress_max\"\nunit = \"yield\"\nupper = 0.5\n{extra}\n",
        10 * last + 5,
        10 * last + 7
    );
    o
}
