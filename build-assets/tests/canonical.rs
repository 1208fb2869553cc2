//! The canonical text and cache key of one spec of every kind, of every FAST spatial and
//! temporal filter and of every sample space, pinned: a change to the canonical text re-keys
//! every cache (committed ones included), so it must be a visible, deliberate break (bump the
//! pins and say so in CHANGELOG.md).

use build_assets::cache::key;
use noisebake_test_support::bake::spec;

const PINS: &[(&str, &str, &str)] = &[
    (
        "kind = \"sampler\"\ndims = [128, 128]",
        "kind=sampler;dims=[128,128];seed=0;format=u16;spp=1;sample_dims=2;spatial_filter={kind=gauss,sigma=1};frames=1",
        "bb506242859dcb0acf2494c0e32d7495",
    ),
    (
        "kind = \"sampler\"\ndims = [64, 32]\nseed = 3\nspp = 16\nsample_dims = 5\nspatial_filter = { kind = \"box\", size = 5 }\nframes = 4",
        "kind=sampler;dims=[64,32];seed=3;format=u16;spp=16;sample_dims=5;spatial_filter={kind=box,size=5};frames=4",
        "9331b9c7d654e814cb118d663307fd71",
    ),
    (
        "kind = \"blue2d\"\ndims = [64, 64]",
        "kind=blue2d;dims=[64,64];seed=0;format=u8;sigma=1.5;initial_density=0.1",
        "c83e05c8c308830ca6050dc2d074be2e",
    ),
    (
        "kind = \"stbn\"\ndims = [64, 64, 16]\nseed = 7\nformat = \"u16\"",
        "kind=stbn;dims=[64,64,16];seed=7;format=u16;sigma_xy=1.9;sigma_t=1.9;initial_density=0.1;histogram=volume",
        "10d1803e1a8578001d4f33fa68419a74",
    ),
    (
        "kind = \"stbn\"\ndims = [32, 32, 8]\nhistogram = \"slice\"\nsigma_xy = 2.1\nsigma_t = 1.5\ninitial_density = 0.2",
        "kind=stbn;dims=[32,32,8];seed=0;format=u8;sigma_xy=2.1;sigma_t=1.5;initial_density=0.2;histogram=slice",
        "beab90ed380cfdf630e5fd4c05f9ade1",
    ),
    (
        "kind = \"vac\"\ndims = [8, 8, 4, 4]\ngroups = [{ axes = [0, 1] }, { axes = [2], sigma = 1.5 }, { axes = [3] }]\ntoroidal = [true, true, false, true]\nformat = \"f32\"",
        "kind=vac;dims=[8,8,4,4];seed=0;format=f32;groups=[{axes=[0,1],sigma=1.9},{axes=[2],sigma=1.5},{axes=[3],sigma=1.9}];toroidal=[true,true,false,true];initial_density=0.1;histogram=volume",
        "36fda9217b4e81e474088e5dac61f680",
    ),
    (
        "kind = \"white\"\ndims = [16, 16, 4]\nseed = 3",
        "kind=white;dims=[16,16,4];seed=3;format=u8",
        "d577806e0a2b37971d8f3042f486b093",
    ),
    (
        "kind = \"independent2d\"\ndims = [32, 32, 8]",
        "kind=independent2d;dims=[32,32,8];seed=0;format=u8;sigma=1.9;initial_density=0.1",
        "edbb2329c2745aa7a9940824b6f572b8",
    ),
    (
        "kind = \"golden\"\ndims = [32, 32, 8]\nformat = \"u16\"",
        "kind=golden;dims=[32,32,8];seed=0;format=u16;sigma=1.9;initial_density=0.1",
        "29bd3e2ec2afe5ca2c3110f6846eb16c",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32]",
        "kind=fast;dims=[32,32];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=none};combine=product;iterations=converged;start=ign",
        "57bf6e8ebcadc6fae4e73dde863b672c",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "3b751188a7d4d4fa75d7a1ce4ff4372e",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nspatial_filter = { kind = \"box\", size = 3 }\ntemporal_filter = { kind = \"box\", size = 4 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=box,size=3};temporal_filter={kind=box,size=4};combine=product;iterations=converged;start=ign",
        "4b7c6fe0ef843ee290d9525ecbdaa206",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 16]\nspatial_filter = { kind = \"binomial\", order = 2 }\ntemporal_filter = { kind = \"gauss\", sigma = 1.2 }",
        "kind=fast;dims=[32,32,16];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=binomial,order=2};temporal_filter={kind=gauss,sigma=1.2};combine=product;iterations=converged;start=ign",
        "c9542b8cabca1f5135b8617f708dace2",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nspatial_filter = { kind = \"none\" }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.1 }\ncombine = { separate = 0.5 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=none};temporal_filter={kind=ema,alpha=0.1,beta=0.1};combine={separate=0.5};iterations=converged;start=ign",
        "571c66bdbd05972cbf4fbc53d368818c",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"none\" }\niterations = 5\nstart = \"random\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=none};combine=product;iterations=5;start=random",
        "5fa3acbf4f6c61cf0313f2143e6848b9",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"taa\" }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=taa,alpha=0.1,coverage=0.2,motion=[0,0],moving=0};combine=product;iterations=converged;start=ign",
        "02ff60a37e7df3567cd244ae6ac8556b",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"taa\", motion = [3, -1] }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=taa,alpha=0.1,coverage=0.2,motion=[3,-1],moving=0.25};combine=product;iterations=converged;start=ign",
        "c41f60914e0bc728f8a0e79aa36c8843",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ndistribution = \"tent\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=tent;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "9545300d31e59b0a8036c401872fed8b",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ndistribution = \"gauss\"\nformat = \"f32\"",
        "kind=fast;dims=[32,32,8];seed=0;format=f32;sample_space=scalar;distribution=gauss;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "0dfe3ccd021dac63e61c8d4b5fcba9e5",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"circle\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=circle;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "4e224e5e4e9f8423b870af2f4c679796",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec2\"\nformat = \"u8x2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x2;sample_space=vec2;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "dbda0e94d73655863c4c7fdb268cd48a",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec3\"\nformat = \"u8x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=vec3;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "5fcfa9fe9b748527bb9629afb4d5809d",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec4\"\nformat = \"u8x4\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x4;sample_space=vec4;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "dd39e25c1c21ccf69db5148b36fd1dcd",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"sphere\"\nformat = \"u8x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=sphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "2b1e4b5839a58fd8609cb0ce151d588c",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"hemisphere\"\nformat = \"f32x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=f32x3;sample_space=hemisphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "95bcae6b6bf5822c8e1ba81c247a46b9",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nspatial_filter = { kind = \"box\", size = 5 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=cosine_hemisphere;distribution=uniform;spatial_filter={kind=box,size=5};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign_r2",
        "81b16a22654b816dc79a285e6abb8907",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nstart = \"ign_r2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=cosine_hemisphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign_r2",
        "657c3224fccbdcb21c471ce4ebc3f4a4",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"sphere\"\nformat = \"u8x3\"\nstart = \"rd_ign_r2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=sphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "2b1e4b5839a58fd8609cb0ce151d588c",
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
