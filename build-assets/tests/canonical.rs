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
        "4e61eddb063e33bccf7e6ecc2c4a5024",
    ),
    (
        "kind = \"sampler\"\ndims = [64, 32]\nseed = 3\nspp = 16\nsample_dims = 5\nspatial_filter = { kind = \"box\", size = 5 }\nframes = 4",
        "kind=sampler;dims=[64,32];seed=3;format=u16;spp=16;sample_dims=5;spatial_filter={kind=box,size=5};frames=4",
        "d5be7390d8c5fa714ac6b68ea8cf57b0",
    ),
    (
        "kind = \"blue2d\"\ndims = [64, 64]",
        "kind=blue2d;dims=[64,64];seed=0;format=u8;sigma=1.5;initial_density=0.1",
        "bda1b2e3e70d33e22326257c7d896fa1",
    ),
    (
        "kind = \"stbn\"\ndims = [64, 64, 16]\nseed = 7\nformat = \"u16\"",
        "kind=stbn;dims=[64,64,16];seed=7;format=u16;sigma_xy=1.9;sigma_t=1.9;initial_density=0.1;histogram=volume",
        "02deb9d484610b20d02b1e204643ce57",
    ),
    (
        "kind = \"stbn\"\ndims = [32, 32, 8]\nhistogram = \"slice\"\nsigma_xy = 2.1\nsigma_t = 1.5\ninitial_density = 0.2",
        "kind=stbn;dims=[32,32,8];seed=0;format=u8;sigma_xy=2.1;sigma_t=1.5;initial_density=0.2;histogram=slice",
        "a26d9835e3f234d9b39dd0a755504f78",
    ),
    (
        "kind = \"vac\"\ndims = [8, 8, 4, 4]\ngroups = [{ axes = [0, 1] }, { axes = [2], sigma = 1.5 }, { axes = [3] }]\ntoroidal = [true, true, false, true]\nformat = \"f32\"",
        "kind=vac;dims=[8,8,4,4];seed=0;format=f32;groups=[{axes=[0,1],sigma=1.9},{axes=[2],sigma=1.5},{axes=[3],sigma=1.9}];toroidal=[true,true,false,true];initial_density=0.1;histogram=volume",
        "fc8172d8fc446a7404504450cd3c2a89",
    ),
    (
        "kind = \"white\"\ndims = [16, 16, 4]\nseed = 3",
        "kind=white;dims=[16,16,4];seed=3;format=u8",
        "7aa3ccc1380d55b5df7c91785b1f23f2",
    ),
    (
        "kind = \"independent2d\"\ndims = [32, 32, 8]",
        "kind=independent2d;dims=[32,32,8];seed=0;format=u8;sigma=1.9;initial_density=0.1",
        "71d7255fd5aa6ce012d5b952ff700931",
    ),
    (
        "kind = \"golden\"\ndims = [32, 32, 8]\nformat = \"u16\"",
        "kind=golden;dims=[32,32,8];seed=0;format=u16;sigma=1.9;initial_density=0.1",
        "4df0a3b3acb718c221f42feffd5878bd",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32]",
        "kind=fast;dims=[32,32];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=none};combine=product;iterations=converged;start=ign",
        "61786f1dc483fb36d0fa4cc1af21af55",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "c9ee3994e5603db631d7ffda33b3cb07",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nspatial_filter = { kind = \"box\", size = 3 }\ntemporal_filter = { kind = \"box\", size = 4 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=box,size=3};temporal_filter={kind=box,size=4};combine=product;iterations=converged;start=ign",
        "2dd8ae44d45229f0af7e220adf46069b",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 16]\nspatial_filter = { kind = \"binomial\", order = 2 }\ntemporal_filter = { kind = \"gauss\", sigma = 1.2 }",
        "kind=fast;dims=[32,32,16];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=binomial,order=2};temporal_filter={kind=gauss,sigma=1.2};combine=product;iterations=converged;start=ign",
        "6b48dd3f1baf0c349cd134e1fece390b",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nspatial_filter = { kind = \"none\" }\ntemporal_filter = { kind = \"ema\", alpha = 0.1, beta = 0.1 }\ncombine = { separate = 0.5 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=none};temporal_filter={kind=ema,alpha=0.1,beta=0.1};combine={separate=0.5};iterations=converged;start=ign",
        "b0a0f10deb0966176746489bb370ac37",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"none\" }\niterations = 5\nstart = \"random\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=none};combine=product;iterations=5;start=random",
        "efffae467ed43c1d2bb960cc6283b8fa",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ntemporal_filter = { kind = \"taa\" }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=taa,alpha=0.1,coverage=0.2};combine=product;iterations=converged;start=ign",
        "7c79f8bbf5c9b6448cb80beddf92f62a",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ndistribution = \"tent\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=scalar;distribution=tent;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "82a591106f0a19fb10148eae3e65a96c",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\ndistribution = \"gauss\"\nformat = \"f32\"",
        "kind=fast;dims=[32,32,8];seed=0;format=f32;sample_space=scalar;distribution=gauss;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "db62cf976ddf2ec7819e746648fd8606",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"circle\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8;sample_space=circle;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign",
        "c79d7fb62ef187a4f2b507efeadc94eb",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec2\"\nformat = \"u8x2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x2;sample_space=vec2;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "2e358ca22c1e674fac0d826fc0877777",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec3\"\nformat = \"u8x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=vec3;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "197687b7a7227d00a6721d4c6739fa5e",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"vec4\"\nformat = \"u8x4\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x4;sample_space=vec4;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=random",
        "f7a6fbb9bc4833706c53bf69d22def86",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"sphere\"\nformat = \"u8x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=sphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "3dbe541febeb42f2f5077a3389739ba9",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"hemisphere\"\nformat = \"f32x3\"",
        "kind=fast;dims=[32,32,8];seed=0;format=f32x3;sample_space=hemisphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "5be77fd31811d885d303210edbd04402",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nspatial_filter = { kind = \"box\", size = 5 }",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=cosine_hemisphere;distribution=uniform;spatial_filter={kind=box,size=5};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign_r2",
        "a08b5730ecf9e5d5900cda941bfa2d52",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"cosine_hemisphere\"\nformat = \"u8x3\"\nstart = \"ign_r2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=cosine_hemisphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=ign_r2",
        "3f3b78a7d44b679850bbd2959faad381",
    ),
    (
        "kind = \"fast\"\ndims = [32, 32, 8]\nsample_space = \"sphere\"\nformat = \"u8x3\"\nstart = \"rd_ign_r2\"",
        "kind=fast;dims=[32,32,8];seed=0;format=u8x3;sample_space=sphere;distribution=uniform;spatial_filter={kind=gauss,sigma=1.3435};temporal_filter={kind=ema,alpha=0.1,beta=0};combine=product;iterations=converged;start=rd_ign_r2",
        "3dbe541febeb42f2f5077a3389739ba9",
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
