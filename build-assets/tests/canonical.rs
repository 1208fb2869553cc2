//! The canonical text and cache key of one spec of every kind, of every FAST spatial and
//! temporal filter and of every sample space, pinned: a change to the canonical text re-keys
//! every cache (committed ones included), so it must be a visible, deliberate break (bump the
//! pins and say so in CHANGELOG.md).

use build_assets::cache::key;
use noisebake_test_support::bake::spec;

const PINS: &[(&str, &str, &str)] = &[
    (
        "kind = \"blue2d\"\ndims = [64, 64]",
        "kind=blue2d;dims=[64,64];seed=0;format=u8;sigma=1.5;initial_density=0.1",
        "883f23744e8c4fb68acf0e8d2359a255",
    ),
    (
        "kind = \"stbn\"\ndims = [64, 64, 16]\nseed = 7\nformat = \"u16\"",
        "kind=stbn;dims=[64,64,16];seed=7;format=u16;sigma_xy=1.9;sigma_t=1.9;initial_density=0.1;histogram=volume",
        "b851ab5777f4d06349cab0edfb7bc483",
    ),
    (
        "kind = \"stbn\"\ndims = [32, 32, 8]\nhistogram = \"slice\"\nsigma_xy = 2.1\nsigma_t = 1.5\ninitial_density = 0.2",
        "kind=stbn;dims=[32,32,8];seed=0;format=u8;sigma_xy=2.1;sigma_t=1.5;initial_density=0.2;histogram=slice",
        "f9e3c771c8f409cf6c2979d015390d5c",
    ),
    (
        "kind = \"vac\"\ndims = [8, 8, 4, 4]\ngroups = [{ axes = [0, 1] }, { axes = [2], sigma = 1.5 }, { axes = [3] }]\ntoroidal = [true, true, false, true]\nformat = \"f32\"",
        "kind=vac;dims=[8,8,4,4];seed=0;format=f32;groups=[{axes=[0,1],sigma=1.9},{axes=[2],sigma=1.5},{axes=[3],sigma=1.9}];toroidal=[true,true,false,true];initial_density=0.1;histogram=volume",
        "85de5da57bc0db3a1da5210112d104dd",
    ),
    (
        "kind = \"white\"\ndims = [16, 16, 4]\nseed = 3",
        "kind=white;dims=[16,16,4];seed=3;format=u8",
        "e061c7be61280a9a7920e5252dcbabfe",
    ),
    (
        "kind = \"independent2d\"\ndims = [32, 32, 8]",
        "kind=independent2d;dims=[32,32,8];seed=0;format=u8;sigma=1.9;initial_density=0.1",
        "47b06e40ce9faad164ac112e2bbb7bed",
    ),
    (
        "kind = \"golden\"\ndims = [32, 32, 8]\nformat = \"u16\"",
        "kind=golden;dims=[32,32,8];seed=0;format=u16;sigma=1.9;initial_density=0.1",
        "3e0124479f258267f2d352ef5ce28401",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32]",
        "kind=fast;dims=[32,32];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=none};combine=product;iterations=converged;start=ign",
        "f3576d151d26c7a24ac2e35566ec6a89",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "765e50c3f698af8a7fcee329380c2813",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nspatial_filter = { kind = \"box\", size = 3 }\ntemporal_filter = { kind = \"box\", size = 4 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=box,size=3};temporal_filter={kind=box,size=4};combine=product;iterations=converged;start=ign",
        "f23aa6f4c77d1013b6d7dfe0e51c7c27",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 16]\nspatial_filter = { kind = \"binomial\", order = 2 }\ntemporal_filter = { kind = \"gauss\", sigma = 1.2 }",
        "kind=fast;dims=[32,32,16];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=binomial,order=2};temporal_filter={kind=gauss,sigma=1.2};combine=product;iterations=converged;start=ign",
        "2cbe6b08df7628e459661a56e03b9e07",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nspatial_filter = { kind = \"none\" }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.1 }\ncombine = { separate = 0.5 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=none};temporal_filter={kind=ema,alpha=0.1,beta=0.1};combine={separate=0.5};iterations=converged;start=ign",
        "24c3f83067d9100eb0bab0cdbb3ba5b3",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"none\" }\niterations = 5\nstart = \"random\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=none};combine=product;iterations=5;start=random",
        "557f5b0f61ffaaceb20016da0a59fc2e",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ndistribution = \"tent\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=tent;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "62dd7e69abae8d78bbbc95b45df70f68",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ndistribution = \"gauss\"\nformat = \"f32\"",
        "kind=fast;dims=[32,32,8];seed=0;format=f32;sample_space=scalar;distribution=gauss;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "28a293544569cb4010b1a6025c51a672",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"circle\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=circle;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "32336dc2d692a4568bd1147fd49cae1f",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec2\"\nformat = \"u8x2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x2;sample_space=vec2;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "81f8fd89ff5ed2471811faea23af7e96",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec3\"\nformat = \"u8x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=vec3;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "236906a2377f3dfefb45e9fe9921f5fa",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec4\"\nformat = \"u8x4\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x4;sample_space=vec4;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "70cb2efd24d538ca1e21ea3db9674e02",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"sphere\"\nformat = \"u8x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=sphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "9ded01074f8bd09d84967defb8e72f74",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"hemisphere\"\nformat = \"f32x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=f32x3;sample_space=hemisphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "ba4732dfb3d6fe16d58cd8013c8a4a4d",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nspatial_filter = { kind = \"box\", size = 5 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=cosine_hemisphere;distribution=uniform;spatial_filter={kind=box,size=5};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "93fdfaa2452ba3ac2a4f96f6a17a4ed6",
    ),
];

#[test]
fn canonical_texts_and_keys_are_pinned() {
    let mut got = String::new();
    for (body, _, _) in PINS {
        let s = spec(body);
        got += &format!(
            "    (\n        {body:?},\n        {:?},\n        {:?},\n    ),\n",
            s.canonical(),
            key(&s)
        );
    }
    if std::env::var_os("NOISEBAKE_PRINT_PINS").is_some() {
        println!("{got}");
    }
    for (body, text, k) in PINS {
        let s = spec(body);
        assert_eq!(s.canonical(), *text, "{body}");
        assert_eq!(key(&s), *k, "{body}");
    }
}

/// Defaults are filled in: a spec that writes every default out has the canonical text (and so
/// the key) of one that leaves them all out, and the name is not part of it.
#[test]
fn defaults_written_out_change_nothing() {
    for (short, long) in [
        (
            "kind = \"stbn\"\ndims = [16, 16, 4]",
            "kind = \"stbn\"\ndims = [16, 16, 4]\nseed = 0\nformat = \"u8\"\nsigma_xy = 1.9\nsigma_t = 1.9\ninitial_density = 0.1\nhistogram = \"volume\"",
        ),
        (
            "kind = \"fast\"\ndims = [16, 16, 4]",
            "kind = \"fast\"\ndims = [16, 16, 4]\nsample_space = \"scalar\"\ndistribution = \"uniform\"\nspatial_filter = { kind = \"gauss\", sigma = 1.3435 }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0 }\ncombine = \"product\"\nstart = \"ign\"",
        ),
    ] {
        assert_eq!(spec(short).canonical(), spec(long).canonical());
    }
    let renamed = build_assets::spec::parse_toml(
        "[[texture]]\nname = \"OTHER\"\nkind = \"white\"\ndims = [4]\n",
    )
    .unwrap()
    .textures
    .remove(0);
    assert_eq!(
        renamed.canonical(),
        spec("kind = \"white\"\ndims = [4]").canonical()
    );
}

/// Every pinned canonical text reads back to its spec: `to_spec` then `canonical` is the
/// identity, which is how `cache verify` knows an entry's text is this version's.
#[test]
fn canonical_text_reads_back() {
    for (_, text, _) in PINS {
        let back =
            build_assets::spec::canonical::to_spec(text).unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(back.canonical(), *text);
    }
    // Text in the pre-0.1 Debug form does not.
    assert!(build_assets::spec::canonical::to_spec(
        "kind=fast;dims=[16,16,4];seed=0;format=u8;sample_space=scalar;distribution=Uniform;spatial=Gauss { sigma: 1.3435 }"
    )
    .is_err());
}
